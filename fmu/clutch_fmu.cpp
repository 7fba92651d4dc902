// The FMI 2.0 co-simulation FMU of the wet clutch (docs/fmu.md): the fmi2* functions around
// rig_models::RealtimeCoupling. Inputs: the two shaft speeds and the clamp force (or apply
// pressure); outputs: torque, heat, interface and sensor temperatures; parameters: the fluid
// file, geometry, steps and the effects (fmu/variables.hpp).
//
// States of an instance (FMI 2.0 section 4.2.4): instantiated → initialisation mode →
// stepping → terminated; fmi2Reset returns to instantiated with every variable at its start.
// The clutch is built when initialisation ends (bad parameters, an unreadable fluid file:
// fmi2Error with the reason sent to the logger). Every call catches its exceptions: nothing
// escapes into the importing tool.
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "core/units.hpp"
#include "fmu/fmi2.h"
#include "fmu/variables.hpp"
#include "io/fluid_loader.hpp"
#include "rig_models/realtime_coupling.hpp"

namespace {

using namespace shudder;
using fmu::Causality;
using fmu::Type;

enum class Phase { kInstantiated, kInitialising, kStepping, kTerminated, kError };

constexpr std::size_t kCount = std::size(fmu::kVariables);

struct Instance {
  std::string name;
  fmi2CallbackFunctions callbacks;
  bool logging = false;
  std::filesystem::path resources;
  Phase phase = Phase::kInstantiated;
  double start_time_s = 0.0, time_s = 0.0;
  std::vector<double> numbers = std::vector<double>(kCount);        // Real, Integer, Boolean
  std::vector<std::string> texts = std::vector<std::string>(kCount);  // String
  std::unique_ptr<clutch::WetClutch> clutch;
  std::unique_ptr<rig_models::RealtimeCoupling> coupling;

  Instance(std::string n, const fmi2CallbackFunctions& cb) : name(std::move(n)), callbacks(cb) { set_starts(); }

  void set_starts() {
    for (std::size_t i = 0; i < kCount; ++i) {
      numbers[i] = fmu::kVariables[i].start;
      texts[i] = std::string(fmu::kVariables[i].start_text);
    }
  }

  // The FMI logger's message is printf-like and '#' starts a value reference: escape both.
  void log(fmi2Status status, const char* category, const std::string& message) const {
    if (!callbacks.logger) return;
    if (status < fmi2Error && !logging) return;  // errors are always reported
    std::string m;
    for (char c : message) {
      if (c == '%' || c == '#') m += c;
      m += c;
    }
    callbacks.logger(callbacks.componentEnvironment, name.c_str(), status, category, m.c_str());
  }
  fmi2Status fail(const std::string& message) {
    log(fmi2Error, "logStatusError", message);
    return fmi2Error;
  }

  double num(unsigned vr) const { return numbers[index(vr)]; }
  static std::size_t index(unsigned vr) {
    for (std::size_t i = 0; i < kCount; ++i)
      if (fmu::kVariables[i].vr == vr) return i;
    return kCount;
  }

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
    if (!(th.outer_radius_m > th.inner_radius_m)) throw std::invalid_argument("outer_radius_mm must exceed inner_radius_mm");
    if (!(num(v::kPistonArea) >= 0.0)) throw std::invalid_argument("piston_area_m2 must be >= 0");
    const std::filesystem::path fluid(texts[index(v::kFluidFile)]);
    const std::filesystem::path path = fluid.is_absolute() ? fluid : resources / fluid;
    if (std::error_code ec; !std::filesystem::is_regular_file(path, ec))
      throw std::invalid_argument("fluid_file: '" + path.string() + "' is not a readable file; give a fluid TOML "
                                  "(absolute, or relative to the FMU's resources/)");
    clutch = std::make_unique<clutch::WetClutch>(p, io::load_fluid(path.string()));
    rig_models::BearingDrag drag;
    drag.enabled = num(v::kBearingDrag) != 0.0;
    drag.equivalent_mu = num(v::kBearingDragMu);
    drag.radius_m = num(v::kBearingDragRadius) * 1e-3;
    coupling = std::make_unique<rig_models::RealtimeCoupling>(
        *clutch, drag, rig_models::RealtimeSettings{num(v::kFixedStep), num(v::kThermalStep)}, force_N());
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
      const double drag = num(v::kBearingDrag) != 0.0 ? num(v::kBearingDragMu) * f * num(v::kBearingDragRadius) * 1e-3 : 0.0;
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

Instance* as_instance(fmi2Component c) { return static_cast<Instance*>(c); }

// Runs `body` with exceptions turned into fmi2Error and a logged message.
template <class Body>
fmi2Status guarded(fmi2Component c, const char* function, Body&& body) {
  if (!c) return fmi2Error;
  Instance* inst = as_instance(c);
  try {
    return body(*inst);
  } catch (const std::exception& e) {
    inst->phase = Phase::kError;
    return inst->fail(std::string(function) + ": " + e.what());
  } catch (...) {
    inst->phase = Phase::kError;
    return inst->fail(std::string(function) + ": unknown error");
  }
}

template <class T, class Read>
fmi2Status get_values(fmi2Component c, const char* function, Type type, const fmi2ValueReference vr[], size_t nvr,
                      T value[], Read read) {
  return guarded(c, function, [&](Instance& inst) {
    for (size_t k = 0; k < nvr; ++k) {
      const std::size_t i = Instance::index(vr[k]);
      if (i == kCount || fmu::kVariables[i].type != type)
        return inst.fail(std::string(function) + ": unknown value reference " + std::to_string(vr[k]) + " for this type");
      value[k] = read(inst, i);
    }
    return fmi2OK;
  });
}

template <class T, class Write>
fmi2Status set_values(fmi2Component c, const char* function, Type type, const fmi2ValueReference vr[], size_t nvr,
                      const T value[], Write write) {
  return guarded(c, function, [&](Instance& inst) {
    for (size_t k = 0; k < nvr; ++k) {
      const std::size_t i = Instance::index(vr[k]);
      if (i == kCount || fmu::kVariables[i].type != type)
        return inst.fail(std::string(function) + ": unknown value reference " + std::to_string(vr[k]) + " for this type");
      const auto& var = fmu::kVariables[i];
      if (var.causality == Causality::kOutput)
        return inst.fail(std::string(function) + ": " + std::string(var.name) + " is an output and cannot be set");
      if (var.causality == Causality::kParameter && inst.phase != Phase::kInstantiated &&
          inst.phase != Phase::kInitialising)
        return inst.fail(std::string(function) + ": parameter " + std::string(var.name) +
                         " is fixed; set it before initialisation ends");
      write(inst, i, value[k]);
    }
    return fmi2OK;
  });
}

fmi2Status unsupported(fmi2Component c, const char* function) {
  return guarded(c, function, [&](Instance& inst) {
    return inst.fail(std::string(function) + " is not supported by this FMU (see modelDescription.xml)");
  });
}

std::filesystem::path resources_from_uri(fmi2String uri) {
  if (!uri) return {};
  std::string s(uri);
  if (s.rfind("file://", 0) == 0) s = s.substr(7);
  else if (s.rfind("file:", 0) == 0) s = s.substr(5);
  // Percent-decoding (RFC 3986) of the path part.
  std::string out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s[k] == '%' && k + 2 < s.size()) {
      out += static_cast<char>(std::stoi(s.substr(k + 1, 2), nullptr, 16));
      k += 2;
    } else {
      out += s[k];
    }
  }
  return out;
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t, const fmi2String[]) {
  return guarded(c, "fmi2SetDebugLogging", [&](Instance& inst) {
    inst.logging = loggingOn != fmi2False;
    return fmi2OK;
  });
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions, fmi2Boolean,
                              fmi2Boolean loggingOn) {
  if (!functions) return nullptr;
  const auto refuse = [&](const std::string& why) -> fmi2Component {
    if (functions->logger)
      functions->logger(functions->componentEnvironment, instanceName ? instanceName : "", fmi2Error,
                        "logStatusError", why.c_str());
    return nullptr;
  };
  try {
    if (fmuType != fmi2CoSimulation) return refuse("fmi2Instantiate: this FMU supports co-simulation only");
    if (!fmuGUID || std::string_view(fmuGUID) != fmu::kGuid)
      return refuse("fmi2Instantiate: GUID does not match this FMU's modelDescription.xml");
    auto inst = std::make_unique<Instance>(instanceName ? instanceName : "", *functions);
    inst->logging = loggingOn != fmi2False;
    inst->resources = resources_from_uri(fmuResourceLocation);
    return inst.release();
  } catch (const std::exception& e) {
    return refuse(std::string("fmi2Instantiate: ") + e.what());
  }
}

void fmi2FreeInstance(fmi2Component c) { delete as_instance(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime, fmi2Boolean, fmi2Real) {
  return guarded(c, "fmi2SetupExperiment", [&](Instance& inst) {
    if (inst.phase != Phase::kInstantiated) return inst.fail("fmi2SetupExperiment: only allowed after fmi2Instantiate");
    inst.start_time_s = inst.time_s = startTime;
    return fmi2OK;
  });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2EnterInitializationMode", [&](Instance& inst) {
    if (inst.phase != Phase::kInstantiated)
      return inst.fail("fmi2EnterInitializationMode: only allowed after fmi2Instantiate/fmi2SetupExperiment");
    inst.phase = Phase::kInitialising;
    return fmi2OK;
  });
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return guarded(c, "fmi2ExitInitializationMode", [&](Instance& inst) {
    if (inst.phase != Phase::kInitialising)
      return inst.fail("fmi2ExitInitializationMode: call fmi2EnterInitializationMode first");
    inst.build();
    inst.update_outputs(false);
    inst.phase = Phase::kStepping;
    return fmi2OK;
  });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  return guarded(c, "fmi2Terminate", [&](Instance& inst) {
    if (inst.phase != Phase::kStepping) return inst.fail("fmi2Terminate: only allowed after initialisation");
    inst.phase = Phase::kTerminated;
    return fmi2OK;
  });
}

fmi2Status fmi2Reset(fmi2Component c) {
  return guarded(c, "fmi2Reset", [&](Instance& inst) {
    inst.coupling.reset();
    inst.clutch.reset();
    inst.set_starts();
    inst.start_time_s = inst.time_s = 0.0;
    inst.phase = Phase::kInstantiated;
    return fmi2OK;
  });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  return get_values(c, "fmi2GetReal", Type::kReal, vr, nvr, value,
                    [](const Instance& inst, std::size_t i) { return inst.numbers[i]; });
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[]) {
  return get_values(c, "fmi2GetInteger", Type::kInteger, vr, nvr, value,
                    [](const Instance& inst, std::size_t i) { return static_cast<fmi2Integer>(inst.numbers[i]); });
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[]) {
  return get_values(c, "fmi2GetBoolean", Type::kBoolean, vr, nvr, value, [](const Instance& inst, std::size_t i) {
    return inst.numbers[i] != 0.0 ? fmi2True : fmi2False;
  });
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[]) {
  return get_values(c, "fmi2GetString", Type::kString, vr, nvr, value,
                    [](const Instance& inst, std::size_t i) { return inst.texts[i].c_str(); });
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  return set_values(c, "fmi2SetReal", Type::kReal, vr, nvr, value,
                    [](Instance& inst, std::size_t i, fmi2Real v) { inst.numbers[i] = v; });
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[]) {
  return set_values(c, "fmi2SetInteger", Type::kInteger, vr, nvr, value,
                    [](Instance& inst, std::size_t i, fmi2Integer v) { inst.numbers[i] = v; });
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[]) {
  return set_values(c, "fmi2SetBoolean", Type::kBoolean, vr, nvr, value,
                    [](Instance& inst, std::size_t i, fmi2Boolean v) { inst.numbers[i] = v != fmi2False ? 1.0 : 0.0; });
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[]) {
  return set_values(c, "fmi2SetString", Type::kString, vr, nvr, value,
                    [](Instance& inst, std::size_t i, fmi2String v) { inst.texts[i] = v ? v : ""; });
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate*) { return unsupported(c, "fmi2GetFMUstate"); }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate) { return unsupported(c, "fmi2SetFMUstate"); }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate*) { return unsupported(c, "fmi2FreeFMUstate"); }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return unsupported(c, "fmi2SerializedFMUstateSize");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return unsupported(c, "fmi2SerializeFMUstate");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return unsupported(c, "fmi2DeSerializeFMUstate");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2ValueReference[],
                                        size_t, const fmi2Real[], fmi2Real[]) {
  return unsupported(c, "fmi2GetDirectionalDerivative");
}
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                       const fmi2Real[]) {
  return unsupported(c, "fmi2SetRealInputDerivatives");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                        fmi2Real[]) {
  return unsupported(c, "fmi2GetRealOutputDerivatives");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean) {
  return guarded(c, "fmi2DoStep", [&](Instance& inst) {
    if (inst.phase != Phase::kStepping)
      return inst.fail("fmi2DoStep: not allowed before fmi2ExitInitializationMode or after fmi2Terminate");
    if (!(communicationStepSize > 0.0))
      return inst.fail("fmi2DoStep: communicationStepSize must be > 0 (got " + std::to_string(communicationStepSize) + ")");
    const double h = inst.coupling->clutch().settings().step_s;
    const double ratio = communicationStepSize / h;
    const double n = std::round(ratio);
    if (n < 1.0 || std::abs(ratio - n) > 1e-9 * n)
      return inst.fail("fmi2DoStep: communicationStepSize must be a whole multiple of fixed_step_s = " +
                       std::to_string(h) + " s");
    if (std::abs(currentCommunicationPoint - inst.time_s) > 1e-9 * std::max(1.0, std::abs(inst.time_s)))
      return inst.fail("fmi2DoStep: currentCommunicationPoint " + std::to_string(currentCommunicationPoint) +
                       " s differs from the FMU's time " + std::to_string(inst.time_s) + " s");
    const double slip = inst.slip_rad_s(), force = inst.force_N();
    for (long k = 0; k < static_cast<long>(n); ++k) inst.coupling->step(slip, force);
    inst.time_s = inst.start_time_s + inst.coupling->time_s();
    inst.update_outputs(true);
    return fmi2OK;
  });
}

fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) { return unsupported(c, "fmi2GetStatus"); }
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  return guarded(c, "fmi2GetRealStatus", [&](Instance& inst) {
    if (s != fmi2LastSuccessfulTime) return inst.fail("fmi2GetRealStatus: only fmi2LastSuccessfulTime is available");
    *value = inst.time_s;
    return fmi2OK;
  });
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return unsupported(c, "fmi2GetIntegerStatus");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  return guarded(c, "fmi2GetBooleanStatus", [&](Instance& inst) {
    if (s != fmi2Terminated) return inst.fail("fmi2GetBooleanStatus: only fmi2Terminated is available");
    *value = fmi2False;  // the FMU never asks the master to stop
    return fmi2OK;
  });
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return unsupported(c, "fmi2GetStringStatus");
}

}  // extern "C"
