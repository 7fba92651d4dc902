// The fmi2* functions every shudder FMU library exports (fmu/fmi2_instance.hpp): the calling
// sequence, logging, get/set by value reference, communication-step checks and the status
// queries, on top of the library's InstanceBase (fmu/clutch_fmu.cpp, fmu/network_fmu.cpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "fmu/fmi2_instance.hpp"

namespace shudder::fmu {

std::size_t InstanceBase::index(unsigned vr) const {
  const std::size_t n = variable_count();
  for (std::size_t i = 0; i < n; ++i)
    if (variable(i).vr == vr) return i;
  return n;
}

StepSplit InstanceBase::split_communication_step(double tc, double H, double h) const {
  const double tol = step_tolerance_s(h, tc, H);
  if (std::abs(tc - time_s) > tol) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "currentCommunicationPoint %.17g s differs from the FMU's time %.17g s", tc, time_s);
    throw CallRefused(std::string("fmi2DoStep: ") + buf);
  }
  const StepSplit split = split_step(H, h, tol);
  if (split.whole_steps > 1e12)
    throw CallRefused("fmi2DoStep: communicationStepSize " + std::to_string(H) + " s is more than 1e12 internal steps");
  return split;
}

void InstanceBase::log_shorter_step(double H, double whole, double fraction) {
  if (shorter_step_logged) return;
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "fmi2DoStep: h = %.17g s is not a whole multiple of fixed_step_s; taken as %.0f internal "
                "steps and one of %.6g of a step (logged once)",
                H, whole, fraction);
  info(buf);
  shorter_step_logged = true;
}

void InstanceBase::log(fmi2Status status, const char* category, const std::string& message) const {
  if (!callbacks.logger) return;
  if (status < fmi2Error &&
      (!logging || (!categories.empty() && !categories.count(category) && !categories.count("logAll"))))
    return;
  std::string m;
  for (char c : message) {
    if (c == '%' || c == '#') m += c;
    m += c;
  }
  callbacks.logger(callbacks.componentEnvironment, name.c_str(), status, category, m.c_str());
}

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
        return ch >= '0' && ch <= '9'   ? ch - '0'
               : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10
               : ch >= 'A' && ch <= 'F' ? ch - 'A' + 10
                                        : -1;
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
  std::transform(lower_host.begin(), lower_host.end(), lower_host.begin(),
                 [](unsigned char ch) { return std::tolower(ch); });
#ifdef _WIN32
  // "/C:/dir" is the drive path "C:/dir"; another host is the share \\host\path.
  if (out.size() >= 3 && out[0] == '/' && std::isalpha(static_cast<unsigned char>(out[1])) && out[2] == ':')
    out = out.substr(1);
  if (!lower_host.empty() && lower_host != "localhost") return {"//" + host + out, ""};
#else
  if (!lower_host.empty() && lower_host != "localhost")
    return {{},
            "the resource location '" + std::string(uri) + "' names the host '" + host +
                "', and only this machine's files can be read here"};
#endif
  return {out, ""};
}

}  // namespace shudder::fmu

namespace {

using namespace shudder;
using fmu::Causality;
using fmu::InstanceBase;
using fmu::Phase;
using fmu::Type;
using Instance = fmu::InstanceBase;

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
      const std::size_t i = inst.index(vr[k]);
      if (i == inst.variable_count() || inst.variable(i).type != type)
        return inst.fail(std::string(function) + ": unknown value reference " + std::to_string(vr[k]) +
                         " for this type");
      if (inst.variable(i).causality == Causality::kOutput) {
        if (inst.phase == Phase::kInstantiated)
          return inst.fail(std::string(function) + ": output " + std::string(inst.variable(i).name) +
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
      const std::size_t i = inst.index(vr[k]);
      if (i == inst.variable_count() || inst.variable(i).type != type)
        return inst.fail(std::string(function) + ": unknown value reference " + std::to_string(vr[k]) +
                         " for this type");
      const fmu::VariableInfo var = inst.variable(i);
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
      if (std::find_if(std::begin(fmu::kLogCategories), std::end(fmu::kLogCategories),
                       [&](const char* n) { return name == n; }) == std::end(fmu::kLogCategories)) {
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
      functions->logger(functions->componentEnvironment, instanceName ? instanceName : "", fmi2Error, "logStatusError",
                        why.c_str());
    return nullptr;
  };
  try {
    if (fmuType != fmi2CoSimulation) return refuse("fmi2Instantiate: this FMU supports co-simulation only");
    const fmu::ResourceLocation where = fmu::resources_from_uri(fmuResourceLocation);
    auto inst = fmu::create_instance(instanceName ? instanceName : "", fmuGUID ? fmuGUID : "", where, *functions);
    inst->logging = loggingOn != fmi2False;
    inst->set_starts();
    inst->info("fmi2Instantiate: co-simulation instance '" + inst->name + "', GUID " + std::string(fmuGUID) +
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
    inst.exit_initialisation();
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
    inst.drop_model();
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
  return get_values(c, "fmi2GetBoolean", Type::kBoolean, vr, nvr, value,
                    [](const Instance& inst, std::size_t i) { return inst.numbers[i] != 0.0 ? fmi2True : fmi2False; });
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
    const double H = communicationStepSize;
    if (!(H > 0.0) || !std::isfinite(H))
      return inst.fail("fmi2DoStep: communicationStepSize must be a finite number > 0 (got " + std::to_string(H) + ")");
    if (!std::isfinite(currentCommunicationPoint))
      return inst.fail("fmi2DoStep: currentCommunicationPoint must be finite");
    try {
      inst.do_step(currentCommunicationPoint, H);
    } catch (const fmu::CallRefused& e) {
      return inst.fail(e.what());
    }
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
