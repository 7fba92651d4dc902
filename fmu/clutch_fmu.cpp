// The FMI 2.0 co-simulation FMU of the wet clutch (docs/fmu.md): the fmi2* functions around
// rig_models::RealtimeCoupling. Inputs: the two shaft speeds and the clamp force (or apply
// pressure); outputs: torque, heat, interface and sensor temperatures; parameters: the fluid
// file, geometry, steps and the effects (fmu/variables.hpp).
//
// The calling sequence, logging and get/set are fmu/fmi2_functions.cpp's (fmu/fmi2_instance.hpp).
// The clutch is built when an output is first read in initialisation mode (so outputs there
// are the clutch's values at the start, not zeros) and again when initialisation ends if a
// parameter changed since (bad parameters, an unreadable fluid file: fmi2Error with the reason
// sent to the logger). Every call catches its exceptions: nothing escapes into the importing
// tool.
//
// Communication steps of any length are honoured (docs/fmu.md "Step sizes"): the inputs are
// held over the step, which is taken as whole internal steps and, when the length is not a
// whole multiple, one shorter internal step at its end; the FMU's time is the master's
// tCurrent + h, so a master's clock round-off never accumulates here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "clutch/wet_clutch.hpp"
#include "core/units.hpp"
#include "fmu/fmi2_instance.hpp"
#include "fmu/step_split.hpp"
#include "fmu/variables.hpp"
#include "shudder_fmu_guid.hpp"  // kGuid, generated with modelDescription.xml
#include "io/fluid_loader.hpp"
#include "rig_models/realtime_coupling.hpp"

namespace {

using namespace shudder;
using fmu::Causality;
using fmu::Type;

constexpr std::size_t kCount = std::size(fmu::kVariables);

class Instance : public fmu::InstanceBase {
 public:
  using InstanceBase::InstanceBase;

  std::size_t variable_count() const override { return kCount; }
  fmu::VariableInfo variable(std::size_t i) const override {
    const auto& v = fmu::kVariables[i];
    return {v.vr, v.name, v.type, v.causality};
  }
  void set_starts() override {
    numbers.assign(kCount, 0.0);
    texts.assign(kCount, "");
    for (std::size_t i = 0; i < kCount; ++i) {
      numbers[i] = fmu::kVariables[i].start;
      texts[i] = std::string(fmu::kVariables[i].start_text);
    }
  }
  void exit_initialisation() override {
    // Build if no output was read in initialisation mode or a parameter changed since; if only
    // the inputs changed, restart at the current clamp force (the first frozen friction's).
    if (!coupling || parameters_changed)
      build();
    else if (force_N() != built_force_N)
      coupling->reset(built_force_N = force_N());
    update_outputs(false);
  }
  void drop_model() override {
    coupling.reset();
    clutch.reset();
  }
  void do_step(double tc, double H) override {
    const double h = coupling->clutch().settings().step_s;
    const fmu::StepSplit split = split_communication_step(tc, H, h);
    // Inputs held over the whole step (zero-order hold). Sub-steps never cross the end of a
    // thermal window, so the handover to the thermal model stays on the internal grid.
    const double slip = slip_rad_s(), force = force_N();
    double left = split.whole_steps + split.last_fraction;  // in internal steps
    // What the subtraction leaves below the window's round-off is not a step (a sub-step of
    // 1e-17 steps after a window's end would show the next window's torque a step early).
    while (left > rig_models::RealtimeClutch::kWindowSlack) {
      const double take = std::min({1.0, left, coupling->clutch().window_steps_left()});
      coupling->step(slip, force, take);
      left -= take;
    }
    if (split.last_fraction > 0.0) log_shorter_step(H, split.whole_steps, split.last_fraction);
    // The master's own tCurrent + h: its next currentCommunicationPoint is computed the same way.
    time_s = tc + H;
    if (split.whole_steps + split.last_fraction > 0.0) update_outputs(true);
  }

  double built_force_N = 0.0;  // the clamp force the clutch's first frozen friction was built at
  std::unique_ptr<clutch::WetClutch> clutch;
  std::unique_ptr<rig_models::RealtimeCoupling> coupling;

  double num(unsigned vr) const { return numbers[index(vr)]; }

  double force_N() const {
    return num(fmu::vr::kClampForce) + num(fmu::vr::kApplyPressure) * num(fmu::vr::kPistonArea);
  }
  double slip_rad_s() const { return num(fmu::vr::kSpeedA) - num(fmu::vr::kSpeedB); }

  // Builds the clutch from the parameters (throws with the reason).
  void build() {
    namespace v = fmu::vr;
    clutch::WetClutchParams p;
    p.sliding_interfaces = static_cast<int>(num(v::kSlidingInterfaces));
    p.start_temp_C = num(v::kStartTemp);
    p.sump_start_temp_C = num(v::kSumpStartTemp);
    p.temperature_dependent_friction = num(v::kTemperatureDependentFriction) != 0.0;
    p.load_dependent_friction = num(v::kLoadDependentFriction) != 0.0;
    p.viscous_shear = num(v::kViscousShear) != 0.0;
    auto& th = p.thermal;
    th.inner_radius_m = num(v::kInnerRadius) * 1e-3;
    th.outer_radius_m = num(v::kOuterRadius) * 1e-3;
    th.radial_cells = static_cast<int>(num(v::kRadialCells));
    th.supply_flow_m3_s = units::ml_min_to_m3_s(num(v::kSupplyFlow));
    th.interface_oil_cooling = num(v::kInterfaceOilCooling) != 0.0;
    th.sump_heating = num(v::kSumpHeating) != 0.0;
    if (!(th.outer_radius_m > th.inner_radius_m))
      throw std::invalid_argument("outer_radius_mm must exceed inner_radius_mm");
    if (!(num(v::kPistonArea) >= 0.0)) throw std::invalid_argument("piston_area_m2 must be >= 0");
    const std::filesystem::path fluid(texts[index(v::kFluidFile)]);
    if (!fluid.is_absolute() && !resources_problem.empty())
      throw std::invalid_argument("fluid_file '" + fluid.string() + "' is relative to the FMU's resources, but " +
                                  resources_problem + "; give an absolute fluid_file");
    const std::filesystem::path path = fluid.is_absolute() ? fluid : resources / fluid;
    if (std::error_code ec; !std::filesystem::is_regular_file(path, ec))
      throw std::invalid_argument("fluid_file: '" + path.string() +
                                  "' is not a readable file; give a fluid TOML "
                                  "(absolute, or relative to the FMU's resources/)");
    coupling.reset();  // it refers to the clutch it replaces
    clutch = std::make_unique<clutch::WetClutch>(p, io::load_fluid(path.string()));
    info("fluid loaded: '" + clutch->fluid().name + "' from " + path.string());
    components::BearingDrag drag;
    drag.enabled = num(v::kBearingDrag) != 0.0;
    drag.equivalent_mu = num(v::kBearingDragMu);
    drag.radius_m = num(v::kBearingDragRadius) * 1e-3;
    built_force_N = force_N();
    coupling = std::make_unique<rig_models::RealtimeCoupling>(
        *clutch, drag, rig_models::RealtimeSettings{num(v::kFixedStep), num(v::kThermalStep)}, built_force_N);
    parameters_changed = false;
    info("clutch built with " + parameter_list());
  }

  // "name = value" for every parameter, for the log. Appended piece by piece: GCC 12 warns
  // (-Wrestrict, falsely) on the temporaries of `a + b + c` here.
  std::string parameter_list() const {
    std::string out;
    for (std::size_t i = 0; i < kCount; ++i) {
      const auto& var = fmu::kVariables[i];
      if (var.causality != Causality::kParameter) continue;
      if (!out.empty()) out.append(", ");
      out.append(var.name).append(" = ");
      char buf[32];
      switch (var.type) {
        case Type::kString: out.append("'").append(texts[i]).append("'"); break;
        case Type::kBoolean: out.append(numbers[i] != 0.0 ? "true" : "false"); break;
        default: std::snprintf(buf, sizeof buf, "%.15g", numbers[i]); out.append(buf);
      }
      if (!var.unit.empty() && var.type == Type::kReal) out.append(" ").append(var.unit);
    }
    return out;
  }

  // Initialisation mode: the outputs at the current parameters and inputs, from start values.
  void initial_outputs() override {
    if (!coupling || parameters_changed) build();
    update_outputs(false);
  }

  // Outputs from the coupling (after a step) or, before the first step, at the current inputs.
  void update_outputs(bool stepped) {
    namespace v = fmu::vr;
    double torque = 0.0, clutch_torque = 0.0, heat = 0.0;
    if (stepped) {
      torque = coupling->torque_Nm();
      clutch_torque = coupling->clutch_torque_Nm();
      heat = coupling->heat_W();
    } else {
      const double w = slip_rad_s(), f = force_N();
      const double kinetic = coupling->clutch().kinetic_torque_Nm(std::abs(w), f);
      const double drag =
          num(v::kBearingDrag) != 0.0 ? num(v::kBearingDragMu) * f * num(v::kBearingDragRadius) * 1e-3 : 0.0;
      torque = std::copysign(kinetic, w);
      clutch_torque = std::copysign(kinetic - drag, w);
      heat = clutch->params().sliding_interfaces * coupling->clutch().ring_torque_Nm().sum() * std::abs(w);
    }
    const auto& th = coupling->thermal();
    numbers[index(v::kTorque)] = torque;
    numbers[index(v::kClutchTorque)] = clutch_torque;
    numbers[index(v::kSlip)] = slip_rad_s();
    numbers[index(v::kHeat)] = heat;
    numbers[index(v::kInterfaceMean)] = th.interface_mean_C;
    numbers[index(v::kInterfaceMax)] = th.interface_max_C;
    numbers[index(v::kThermocouple)] = th.thermocouple_C;
    numbers[index(v::kIr)] = th.ir_C;
    numbers[index(v::kSump)] = th.sump_C;
  }
};

}  // namespace

namespace shudder::fmu {

std::unique_ptr<InstanceBase> create_instance(const std::string& instance_name, std::string_view guid,
                                              const ResourceLocation& where, const fmi2CallbackFunctions& cb) {
  if (guid != kGuid) throw Refusal("GUID does not match this FMU's modelDescription.xml");
  return std::make_unique<Instance>(instance_name, cb, where);
}

}  // namespace shudder::fmu
