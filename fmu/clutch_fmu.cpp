// The FMI 2.0 co-simulation FMU of the wet clutch (docs/fmu.md): the fmi2* functions around
// rig_models::RealtimeCoupling. Inputs: the two shaft speeds and the clamp force (or apply
// pressure); outputs: torque, heat, interface and sensor temperatures; parameters: the fluid
// file, geometry, steps and the effects (fmu/variables.hpp).
//
// States of an instance (FMI 2.0 section 4.2.4): instantiated → initialisation mode →
// stepping → terminated; fmi2Reset returns to instantiated with every variable at its start.
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
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "core/units.hpp"
#include "fmu/fmi2.h"
#include "fmu/step_split.hpp"
#include "fmu/variables.hpp"
#include "shudder_fmu_guid.hpp"  // kGuid, generated with modelDescription.xml
#include "io/fluid_loader.hpp"
#include "rig_models/realtime_coupling.hpp"

namespace {

using namespace shudder;
using fmu::Causality;
using fmu::Type;

enum class Phase { kInstantiated, kInitialising, kStepping, kTerminated, kError };

constexpr std::size_t kCount = std::size(fmu::kVariables);

// The log categories of modelDescription.xml (model_description.cpp writes the same list).
constexpr const char* kCategories[] = {"logEvents", "logStatusWarning", "logStatusDiscard", "logStatusError",
                                       "logAll"};

struct Instance {
  std::string name;
  fmi2CallbackFunctions callbacks;
  bool logging = false;
  std::set<std::string> categories;  // empty: every category (fmi2SetDebugLogging with none named)
  std::filesystem::path resources;
  std::string resources_problem;  // why the resource location could not be used ("" if it could)
  Phase phase = Phase::kInstantiated;
  double start_time_s = 0.0, time_s = 0.0;
  bool parameters_changed = true;  // since the clutch was built
  double built_force_N = 0.0;      // the clamp force the clutch's first frozen friction was built at
  bool shorter_step_logged = false;
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
  // Errors are always reported; the rest only with logging on and the category enabled.
  void log(fmi2Status status, const char* category, const std::string& message) const {
    if (!callbacks.logger) return;
    if (status < fmi2Error && (!logging || (!categories.empty() && !categories.count(category) &&
                                            !categories.count("logAll"))))
      return;
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
  void info(const std::string& message) const { log(fmi2OK, "logEvents", message); }

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
    if (!fluid.is_absolute() && !resources_problem.empty())
      throw std::invalid_argument("fluid_file '" + fluid.string() + "' is relative to the FMU's resources, but " +
                                  resources_problem + "; give an absolute fluid_file");
    const std::filesystem::path path = fluid.is_absolute() ? fluid : resources / fluid;
    if (std::error_code ec; !std::filesystem::is_regular_file(path, ec))
      throw std::invalid_argument("fluid_file: '" + path.string() + "' is not a readable file; give a fluid TOML "
                                  "(absolute, or relative to the FMU's resources/)");
    coupling.reset();  // it refers to the clutch it replaces
    clutch = std::make_unique<clutch::WetClutch>(p, io::load_fluid(path.string()));
    info("fluid loaded: '" + clutch->fluid().name + "' from " + path.string());
    rig_models::BearingDrag drag;
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
        default:
          std::snprintf(buf, sizeof buf, "%.15g", numbers[i]);
          out.append(buf);
      }
      if (!var.unit.empty() && var.type == Type::kReal) out.append(" ").append(var.unit);
    }
    return out;
  }

  // Initialisation mode: the outputs at the current parameters and inputs, from start values.
  void initial_outputs() {
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
    bool outputs_ready = inst.phase != Phase::kInitialising;
    for (size_t k = 0; k < nvr; ++k) {
      const std::size_t i = Instance::index(vr[k]);
      if (i == kCount || fmu::kVariables[i].type != type)
        return inst.fail(std::string(function) + ": unknown value reference " + std::to_string(vr[k]) + " for this type");
      if (fmu::kVariables[i].causality == Causality::kOutput) {
        if (inst.phase == Phase::kInstantiated)
          return inst.fail(std::string(function) + ": output " + std::string(fmu::kVariables[i].name) +
                           " is defined from fmi2EnterInitializationMode on");
        if (!outputs_ready) {  // initialisation mode: computed from the current parameters and inputs
          inst.initial_outputs();
          outputs_ready = true;
        }
      }
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
      if (var.causality == Causality::kParameter) inst.parameters_changed = true;
    }
    return fmi2OK;
  });
}

fmi2Status unsupported(fmi2Component c, const char* function) {
  return guarded(c, function, [&](Instance& inst) {
    return inst.fail(std::string(function) + " is not supported by this FMU (see modelDescription.xml)");
  });
}

// A status this FMU does not provide: FMI 2.0 section 4.2.3 answers fmi2Discard (the status
// is not available; the instance carries on), not fmi2Error (the instance cannot go on).
fmi2Status status_not_available(fmi2Component c, const char* function, const std::string& what) {
  return guarded(c, function, [&](Instance& inst) {
    inst.log(fmi2Discard, "logStatusDiscard", std::string(function) + ": " + what + " is not provided by this FMU");
    return fmi2Discard;
  });
}

std::string status_kind_name(fmi2StatusKind s) {
  switch (s) {
    case fmi2DoStepStatus: return "fmi2DoStepStatus";
    case fmi2PendingStatus: return "fmi2PendingStatus";
    case fmi2LastSuccessfulTime: return "fmi2LastSuccessfulTime";
    case fmi2Terminated: return "fmi2Terminated";
  }
  return "status kind " + std::to_string(static_cast<int>(s));
}

struct ResourceLocation {
  std::filesystem::path path;
  std::string problem;  // "" when `path` is usable
};

// fmuResourceLocation is a URI (FMI 2.0 section 2.1.7, RFC 8089): file:///path,
// file://localhost/path, file://host/path (another machine: a UNC path on Windows), or the
// short file:/path; on Windows the path starts with a drive (file:///C:/…). The path part is
// percent-decoded (RFC 3986). A location that cannot be read is not fatal until a relative
// fluid_file needs the resources.
ResourceLocation resources_from_uri(fmi2String uri) {
  if (!uri || !*uri) return {{}, "no resource location was given"};
  std::string s(uri);
  std::string host;
  if (s.rfind("file://", 0) == 0) {
    s = s.substr(7);
    const std::size_t slash = s.find('/');
    host = s.substr(0, slash);
    s = slash == std::string::npos ? std::string("/") : s.substr(slash);
  } else if (s.rfind("file:", 0) == 0) {
    s = s.substr(5);
  } else {
    return {{}, "the resource location '" + std::string(uri) + "' is not a file: URI"};
  }
  std::string out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s[k] == '%') {
      const auto hex = [](char ch) {
        return ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10 : ch >= 'A' && ch <= 'F' ? ch - 'A' + 10 : -1;
      };
      if (k + 2 >= s.size() || hex(s[k + 1]) < 0 || hex(s[k + 2]) < 0)
        return {{}, "the resource location '" + std::string(uri) + "' has a malformed %-escape"};
      out += static_cast<char>(hex(s[k + 1]) * 16 + hex(s[k + 2]));
      k += 2;
    } else {
      out += s[k];
    }
  }
  std::string lower_host = host;
  std::transform(lower_host.begin(), lower_host.end(), lower_host.begin(), [](unsigned char ch) { return std::tolower(ch); });
#ifdef _WIN32
  // "/C:/dir" is the drive path "C:/dir"; another host is the share \\host\path.
  if (out.size() >= 3 && out[0] == '/' && std::isalpha(static_cast<unsigned char>(out[1])) && out[2] == ':')
    out = out.substr(1);
  if (!lower_host.empty() && lower_host != "localhost") return {"//" + host + out, ""};
#else
  if (!lower_host.empty() && lower_host != "localhost")
    return {{}, "the resource location '" + std::string(uri) + "' names the host '" + host +
                    "', and only this machine's files can be read here"};
#endif
  return {out, ""};
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[]) {
  return guarded(c, "fmi2SetDebugLogging", [&](Instance& inst) {
    inst.logging = loggingOn != fmi2False;
    inst.categories.clear();
    fmi2Status status = fmi2OK;
    for (size_t k = 0; k < nCategories && categories; ++k) {
      const std::string name = categories[k] ? categories[k] : "";
      if (std::find_if(std::begin(kCategories), std::end(kCategories), [&](const char* n) { return name == n; }) ==
          std::end(kCategories)) {
        inst.log(fmi2Warning, "logStatusWarning",
                 "fmi2SetDebugLogging: unknown log category '" + name + "' ignored (see modelDescription.xml)");
        status = fmi2Warning;
        continue;
      }
      inst.categories.insert(name);
    }
    // Categories were named but none is known: nothing may be logged but errors.
    if (nCategories > 0 && inst.categories.empty()) inst.categories.insert("none");
    return status;
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
    const ResourceLocation where = resources_from_uri(fmuResourceLocation);
    inst->resources = where.path;
    inst->resources_problem = where.problem;
    inst->info("fmi2Instantiate: co-simulation instance '" + inst->name + "', GUID " + std::string(fmu::kGuid) +
               ", resources " + (where.problem.empty() ? where.path.string() : "unusable: " + where.problem));
    return inst.release();
  } catch (const std::exception& e) {
    return refuse(std::string("fmi2Instantiate: ") + e.what());
  }
}

void fmi2FreeInstance(fmi2Component c) { delete as_instance(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean, fmi2Real, fmi2Real startTime, fmi2Boolean, fmi2Real) {
  return guarded(c, "fmi2SetupExperiment", [&](Instance& inst) {
    if (inst.phase != Phase::kInstantiated) return inst.fail("fmi2SetupExperiment: only allowed after fmi2Instantiate");
    if (!std::isfinite(startTime)) return inst.fail("fmi2SetupExperiment: startTime must be finite");
    inst.start_time_s = inst.time_s = startTime;
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g s", startTime);
    inst.info(std::string("fmi2SetupExperiment: start time ") + buf);
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
    // Build if no output was read in initialisation mode or a parameter changed since; if only
    // the inputs changed, restart at the current clamp force (the first frozen friction's).
    if (!inst.coupling || inst.parameters_changed) inst.build();
    else if (inst.force_N() != inst.built_force_N) inst.coupling->reset(inst.built_force_N = inst.force_N());
    inst.update_outputs(false);
    inst.phase = Phase::kStepping;
    inst.info("fmi2ExitInitializationMode: stepping from t = " + std::to_string(inst.time_s) + " s");
    return fmi2OK;
  });
}

fmi2Status fmi2Terminate(fmi2Component c) {
  return guarded(c, "fmi2Terminate", [&](Instance& inst) {
    if (inst.phase != Phase::kStepping) return inst.fail("fmi2Terminate: only allowed after initialisation");
    inst.phase = Phase::kTerminated;
    inst.info("fmi2Terminate: at t = " + std::to_string(inst.time_s) + " s");
    return fmi2OK;
  });
}

fmi2Status fmi2Reset(fmi2Component c) {
  return guarded(c, "fmi2Reset", [&](Instance& inst) {
    inst.coupling.reset();
    inst.clutch.reset();
    inst.set_starts();
    inst.start_time_s = inst.time_s = 0.0;
    inst.parameters_changed = true;
    inst.shorter_step_logged = false;
    inst.phase = Phase::kInstantiated;
    inst.info("fmi2Reset: back to the start values");
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
    const double tc = currentCommunicationPoint, H = communicationStepSize;
    if (!(H > 0.0) || !std::isfinite(H))
      return inst.fail("fmi2DoStep: communicationStepSize must be a finite number > 0 (got " + std::to_string(H) + ")");
    const double h = inst.coupling->clutch().settings().step_s;
    const double tol = fmu::step_tolerance_s(h, tc, H);
    if (!std::isfinite(tc) || std::abs(tc - inst.time_s) > tol) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "currentCommunicationPoint %.17g s differs from the FMU's time %.17g s", tc,
                    inst.time_s);
      return inst.fail(std::string("fmi2DoStep: ") + buf);
    }
    const fmu::StepSplit split = fmu::split_step(H, h, tol);
    if (split.whole_steps > 1e12)
      return inst.fail("fmi2DoStep: communicationStepSize " + std::to_string(H) + " s is more than 1e12 internal steps");
    // Inputs held over the whole step (zero-order hold). Sub-steps never cross the end of a
    // thermal window, so the handover to the thermal model stays on the internal grid.
    const double slip = inst.slip_rad_s(), force = inst.force_N();
    double left = split.whole_steps + split.last_fraction;  // in internal steps
    // What the subtraction leaves below the window's round-off is not a step (a sub-step of
    // 1e-17 steps after a window's end would show the next window's torque a step early).
    while (left > rig_models::RealtimeClutch::kWindowSlack) {
      const double take = std::min({1.0, left, inst.coupling->clutch().window_steps_left()});
      inst.coupling->step(slip, force, take);
      left -= take;
    }
    if (split.last_fraction > 0.0 && !inst.shorter_step_logged) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "fmi2DoStep: h = %.17g s is not a whole multiple of fixed_step_s; taken as %.0f internal "
                    "steps and one of %.6g of a step (logged once)",
                    H, split.whole_steps, split.last_fraction);
      inst.info(buf);
      inst.shorter_step_logged = true;
    }
    // The master's own tCurrent + h: its next currentCommunicationPoint is computed the same way.
    inst.time_s = tc + H;
    if (split.whole_steps + split.last_fraction > 0.0) inst.update_outputs(true);
    return fmi2OK;
  });
}

fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status*) {
  // fmi2DoStepStatus exists for asynchronous steps (fmi2Pending), which this FMU never returns.
  return status_not_available(c, "fmi2GetStatus", status_kind_name(s));
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real* value) {
  if (s != fmi2LastSuccessfulTime) return status_not_available(c, "fmi2GetRealStatus", status_kind_name(s));
  return guarded(c, "fmi2GetRealStatus", [&](Instance& inst) {
    if (!value) return inst.fail("fmi2GetRealStatus: value is a null pointer");
    *value = inst.time_s;
    return fmi2OK;
  });
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer*) {
  return status_not_available(c, "fmi2GetIntegerStatus", status_kind_name(s));
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean* value) {
  if (s != fmi2Terminated) return status_not_available(c, "fmi2GetBooleanStatus", status_kind_name(s));
  return guarded(c, "fmi2GetBooleanStatus", [&](Instance& inst) {
    if (!value) return inst.fail("fmi2GetBooleanStatus: value is a null pointer");
    *value = fmi2False;  // the FMU never asks the master to stop
    return fmi2OK;
  });
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String*) {
  return status_not_available(c, "fmi2GetStringStatus", status_kind_name(s));
}

}  // extern "C"
