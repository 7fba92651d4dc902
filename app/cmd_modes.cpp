// `shudder modes`: natural frequencies, mode shapes and damped eigenvalues of a rig scenario's
// torsional network, with the clutch slipping (no stiffness through the contact) and stuck.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <variant>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "core/units.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"

namespace shudder::app {

namespace {

void print_modes(const dynamics::TorsionalNetwork& net, const dynamics::Modes& m, const char* title) {
  std::printf("%s\n  mode  frequency [Hz]   shape:", title);
  for (const auto& in : net.inertias()) std::printf(" %10s", in.name.c_str());
  std::printf("\n");
  for (Eigen::Index j = 0; j < m.frequencies_Hz.size(); ++j) {
    std::printf("  %4ld  %14.3f         ", static_cast<long>(j + 1), m.frequencies_Hz[j]);
    for (Eigen::Index i = 0; i < m.shapes.rows(); ++i) std::printf(" %10.4f", m.shapes(i, j));
    std::printf("\n");
  }
  std::printf("  damped eigenvalues (oscillatory ones once, real ones all):\n");
  std::printf("     real [1/s]      imag [1/s]   frequency [Hz]   damping ratio\n");
  for (Eigen::Index k = 0; k < m.damped_eigenvalues.size(); ++k) {
    auto l = m.damped_eigenvalues[k];
    if (std::abs(l.imag()) < 1e-6 * std::max(1.0, std::abs(l))) l.imag(0.0);  // real (a double root splits by ~sqrt(eps))
    if (l.imag() < 0) continue;
    std::printf("  %12.4f  %14.4f   %14.3f   %13.5f\n", l.real(), l.imag(),
                l.imag() / units::kTwoPi, -l.real() / std::abs(l));
  }
}

void print_rig_modes(const io::Scenario& sc, const rig_models::RigModel& model) {
  const clutch::WetClutch clutch = sc.make_clutch();
  const rig_models::LsctrRig rig(model.params, clutch, model.cycle);
  const auto& net = rig.network();
  std::printf("Scenario %s: torsion bar %.6g N m/rad (c = %.4g N m s/rad), speed loop Kp %.4g N m s/rad, "
              "Ki %.4g N m/rad\n\n",
              sc.name.c_str(), rig.bar_stiffness_Nm_per_rad(), rig.bar_damping_Nms_per_rad(),
              rig.motor_kp(), rig.motor_ki());
  print_modes(net, net.modes({false}), "Clutch slipping:");
  std::printf("\n");
  print_modes(net, net.modes({true}), "Clutch stuck:");
  std::printf("\nClutch-side mode (slipping): %.3f Hz\n", rig.clutch_side_frequency_Hz());
}

}  // namespace

int modes_command(const ModesOptions& opt) {
  return guarded(opt.scenario, "modal analysis", [&]() -> int {
    const io::Scenario sc = io::load_scenario(opt.scenario);
    for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
    const rig_models::RigModel& rig = io::visit_kind(
        opt.scenario, "scenario.type", sc.model,
        [](const auto& m) -> const rig_models::RigModel& { return rig_models::modal_rig(m); });
    print_rig_modes(sc, rig);
    return 0;
  });
}

}  // namespace shudder::app
