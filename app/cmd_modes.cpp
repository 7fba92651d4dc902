// `shudder modes`: natural frequencies, mode shapes and damped eigenvalues of a rig scenario's
// torsional network, with the clutch slipping (no stiffness through the contact) and stuck; for
// a driveline, its linearisation about the manoeuvre's quasi-static operating point with the
// coupling slipping and locked (studies/driveline_stability.hpp); for a network, every clutch
// slipping, every clutch stuck and each clutch alone slipping.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <variant>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "core/overloaded.hpp"
#include "core/units.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/network_scenario.hpp"
#include "components/network_builder.hpp"
#include "io/scenario.hpp"
#include "studies/driveline_stability.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/model.hpp"

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
    if (std::abs(l.imag()) < 1e-6 * std::max(1.0, std::abs(l)))
      l.imag(0.0);  // real (a double root splits by ~sqrt(eps))
    if (l.imag() < 0) continue;
    std::printf("  %12.4f  %14.4f   %14.3f   %13.5f\n", l.real(), l.imag(), l.imag() / units::kTwoPi,
                -l.real() / std::abs(l));
  }
}

void print_rig_modes(const io::Scenario& sc, const rig_models::RigModel& model) {
  const clutch::WetClutch clutch = sc.make_clutch();
  const rig_models::LsctrRig rig(model.params, clutch, model.cycle);
  const components::OwnedNetwork built = rig.build();
  const auto& net = built.network();
  std::printf(
      "Scenario %s: torsion bar %.6g N m/rad (c = %.4g N m s/rad), speed loop Kp %.4g N m s/rad, "
      "Ki %.4g N m/rad\n\n",
      sc.name.c_str(), rig.bar_stiffness_Nm_per_rad(), rig.bar_damping_Nms_per_rad(), rig.motor_kp(), rig.motor_ki());
  print_modes(net, net.modes({false}), "Clutch slipping:");
  std::printf("\n");
  print_modes(net, net.modes({true}), "Clutch stuck:");
  std::printf("\nClutch-side mode (slipping): %.3f Hz\n", rig.clutch_side_frequency_Hz());
}

// One driveline mode per line: eigenvalue, frequency, damping ratio and the parts that move
// (|speed| ≥ 0.1 of the largest; a sign for parts in or against phase, else the phase in degrees).
void print_driveline_modes(const studies::DrivelineStability& st, const char* title) {
  std::printf("%s\n     real [1/s]      imag [1/s]   frequency [Hz]   damping ratio   shape (node speed / largest)\n",
              title);
  for (const auto& m : st.modes) {
    std::printf("  %12.4f  %14.4f   %14.3f   %13.5f  ", m.eigenvalue.real(), m.eigenvalue.imag(), m.frequency_Hz,
                m.damping_ratio);
    for (Eigen::Index i = 0; i < m.node_amplitude.size(); ++i) {
      if (m.node_amplitude[i] < 0.1) continue;
      const double deg = m.node_phase_rad[i] * 180.0 / 3.141592653589793;
      if (std::abs(deg) < 20.0)
        std::printf(" %s %+.2f", st.node_names[static_cast<std::size_t>(i)].c_str(), m.node_amplitude[i]);
      else if (std::abs(deg) > 160.0)
        std::printf(" %s %+.2f", st.node_names[static_cast<std::size_t>(i)].c_str(), -m.node_amplitude[i]);
      else
        std::printf(" %s %.2f@%.0fdeg", st.node_names[static_cast<std::size_t>(i)].c_str(), m.node_amplitude[i], deg);
    }
    std::printf("\n");
  }
}

void print_driveline(const io::Scenario& sc, const rig_models::DrivelineModel& model, const std::string& run) {
  const clutch::WetClutch clutch = sc.make_clutch();
  const rig_models::HaldexDriveline dl(model.params, clutch, model.manoeuvre);
  studies::DrivelineOperatingPoint op;
  if (run.empty()) {
    op = studies::quasi_static_operating_point(dl, clutch, model.manoeuvre);
  } else {
    // The run's mean operating point: the one its summary's shuffle mode is linearised at.
    const dynamics::Recording rec = io::read_run_hdf5(run);
    const auto* t = rec.find("time_s");
    if (!t || t->values.empty()) throw io::InputError(run, 0, "time_s", "the run file has no time channel");
    try {
      op = studies::recorded_operating_point(rec, 0.0, t->values.back());
    } catch (const std::invalid_argument& e) {
      throw io::InputError(run, 0, "--run",
                           std::string("is not a driveline run this command can linearise: ") + e.what());
    }
    std::printf("At the mean operating point of %s (0 to %.4g s)\n", run.c_str(), t->values.back());
  }
  const auto slipping = studies::driveline_stability(dl, clutch, op, false);
  const auto locked = studies::driveline_stability(dl, clutch, op, true);
  std::printf(
      "Scenario %s: driveline linearised at %.3g km/h, coupling slip %.4g rpm, clamp force %.5g N, "
      "interface %.4g degC; tyre forces FL/FR/RL/RR %.4g/%.4g/%.4g/%.4g N\n",
      sc.name.c_str(), op.vehicle_speed_m_s * 3.6, units::rad_s_to_rpm(op.coupling_slip_rad_s), op.clamp_force_N,
      op.interface_temp_C, op.tyre_force_N[0], op.tyre_force_N[1], op.tyre_force_N[2], op.tyre_force_N[3]);
  std::printf("Coupling friction slope (isothermal) dM/d|dw| = %.5g N m s/rad\n\n", slipping.coupling_slope_Nms);
  print_driveline_modes(slipping, "Coupling slipping:");
  std::printf("\n");
  print_driveline_modes(locked, "Coupling locked:");
  const auto least = studies::least_damped_mode(slipping);
  std::printf("\nLeast-damped oscillatory mode (slipping): %.3f Hz, growth rate %.4g 1/s, damping ratio %.4g: %s\n",
              least.frequency_Hz, least.growth_per_s, least.damping_ratio,
              least.growth_per_s > 0 ? "UNSTABLE (judder predicted)" : "stable");
}

// A network: its modes with every clutch slipping, every clutch stuck, and (with several
// clutches) each clutch alone slipping; freewheels locked (their driving direction). Shapes are
// named by the nodes; a slipping clutch adds no stiffness (dynamics::TorsionalNetwork::modes).
void print_network_modes(const std::string& path) {
  const io::NetworkScenario sc = io::load_network_scenario(path);
  for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
  const auto built = components::build_network(sc.spec);
  const auto& net = built->network;
  const std::size_t nc = built->clutches.size(), nf = built->freewheel_contacts.size();
  const auto stuck_set = [&](int slipping) {  // -1: all slipping, -2: all stuck, c: only c slipping
    std::vector<bool> stuck(nc + nf, true);
    for (std::size_t c = 0; c < nc; ++c)
      stuck[c] = slipping == -2 || (slipping >= 0 && static_cast<int>(c) != slipping);
    return stuck;
  };
  std::printf("Scenario %s (network): %d nodes, %zu clutches, %zu freewheels (locked)\n\n", sc.name.c_str(),
              net.nodes(), nc, nf);
  print_modes(net, net.modes(stuck_set(-1)), nc ? "Every clutch slipping:" : "Modes:");
  if (nc == 0) return;
  std::printf("\n");
  print_modes(net, net.modes(stuck_set(-2)), "Every clutch stuck:");
  if (nc < 2) return;
  for (std::size_t c = 0; c < nc; ++c) {
    std::printf("\n");
    const std::string title = "Clutch " + built->clutches[c].name() + " slipping, the others stuck:";
    print_modes(net, net.modes(stuck_set(static_cast<int>(c))), title.c_str());
  }
}

}  // namespace

int modes_command(const ModesOptions& opt) {
  return guarded(opt.scenario, "modal analysis", [&]() -> int {
    if (!opt.run.empty() && io::scenario_type(opt.scenario) != "driveline")
      throw io::InputError(opt.scenario, 0, "--run",
                           "linearises a driveline scenario at a run's operating point; this scenario is type = \"" +
                               io::scenario_type(opt.scenario) + "\" (remove --run)");
    if (io::scenario_type(opt.scenario) == "network") {
      print_network_modes(opt.scenario);
      return 0;
    }
    const io::Scenario sc = io::load_scenario(opt.scenario);
    for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
    const rig_models::ModalSubject subject = io::visit_kind(opt.scenario, "scenario.type", sc.model,
                                                            [](const auto& m) { return rig_models::modal_subject(m); });
    std::visit(overloaded{[&](const rig_models::RigModel* rig) { print_rig_modes(sc, *rig); },
                          [&](const rig_models::DrivelineModel* dl) { print_driveline(sc, *dl, opt.run); }},
               subject);
    return 0;
  });
}

}  // namespace shudder::app
