#pragma once
// What every shudder FMU library shares (docs/fmu.md): an instance's life (FMI 2.0 section
// 4.2.4: instantiated → initialisation mode → stepping → terminated; fmi2Reset returns to
// instantiated with every variable at its start), its logger, its resource location, the
// get/set of its variables by value reference and the status queries. fmu/fmi2_functions.cpp
// defines every fmi2* function on top of InstanceBase; a library (fmu/clutch_fmu.cpp,
// fmu/network_fmu.cpp) derives its instance from it and defines fmu::create_instance.
//
// Every fmi2* call catches its exceptions: nothing escapes into the importing tool; an
// exception puts the instance in the error state with the reason sent to the logger.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fmu/fmi2.h"
#include "fmu/step_split.hpp"

namespace shudder::fmu {

enum class Type { kReal, kInteger, kBoolean, kString };
enum class Causality { kParameter, kInput, kOutput };
enum class Phase { kInstantiated, kInitialising, kStepping, kTerminated, kError };

/// The log categories of every modelDescription.xml (fmu/model_description_xml.hpp writes them).
inline constexpr const char* kLogCategories[] = {"logEvents", "logStatusWarning", "logStatusDiscard", "logStatusError",
                                                 "logAll"};

struct ResourceLocation {
  std::filesystem::path path;
  std::string problem;  // "" when `path` is usable
};

/// fmuResourceLocation is a URI (FMI 2.0 section 2.1.7, RFC 8089): file:///path,
/// file://localhost/path, file://host/path (another machine: a UNC path on Windows), or the
/// short file:/path; on Windows the path starts with a drive (file:///C:/…). The path part is
/// percent-decoded (RFC 3986). A location that cannot be read is reported in `problem`.
ResourceLocation resources_from_uri(fmi2String uri);

/// A variable as the instance serves it.
struct VariableInfo {
  unsigned vr;
  std::string_view name;
  Type type;
  Causality causality;
};

class InstanceBase {
 public:
  InstanceBase(std::string instance_name, const fmi2CallbackFunctions& cb, ResourceLocation where)
      : name(std::move(instance_name)),
        callbacks(cb),
        resources(std::move(where.path)),
        resources_problem(std::move(where.problem)) {}
  virtual ~InstanceBase() = default;

  // The FMU's variables, in modelDescription.xml's order.
  virtual std::size_t variable_count() const = 0;
  virtual VariableInfo variable(std::size_t i) const = 0;
  /// Every variable at its start value (numbers: Real, Integer, Boolean; texts: String).
  virtual void set_starts() = 0;
  /// Initialisation mode: the outputs at the current parameters and inputs.
  virtual void initial_outputs() = 0;
  /// fmi2ExitInitializationMode: ready to step from time_s.
  virtual void exit_initialisation() = 0;
  /// fmi2Reset: what the instance built is dropped (starts, phase and times are reset here).
  virtual void drop_model() = 0;
  /// One communication step from time_s (== the master's tc to the step tolerance) of H > 0 s.
  virtual void do_step(double tc_s, double H_s) = 0;

  /// The communication step from tc of H as internal steps of h (fmu/step_split.hpp); throws
  /// CallRefused unless tc is the instance's time to the step tolerance, or for more than 1e12
  /// internal steps.
  StepSplit split_communication_step(double tc_s, double H_s, double h_s) const;
  /// Logs (once per instance, logEvents) that the step H was taken as `whole` internal steps and
  /// one of `fraction` of a step.
  void log_shorter_step(double H_s, double whole, double fraction);
  /// The index of value reference `vr` (variable_count() for none).
  std::size_t index(unsigned vr) const;

  // The FMI logger's message is printf-like and '#' starts a value reference: escaped.
  // Errors are always reported; the rest only with logging on and the category enabled.
  void log(fmi2Status status, const char* category, const std::string& message) const;
  fmi2Status fail(const std::string& message) {
    log(fmi2Error, "logStatusError", message);
    return fmi2Error;
  }
  void info(const std::string& message) const { log(fmi2OK, "logEvents", message); }

  std::string name;
  fmi2CallbackFunctions callbacks;
  bool logging = false;
  std::set<std::string> categories;  // empty: every category (fmi2SetDebugLogging with none named)
  std::filesystem::path resources;
  std::string resources_problem;  // why the resource location could not be used ("" if it could)
  Phase phase = Phase::kInstantiated;
  double start_time_s = 0.0, time_s = 0.0;
  bool parameters_changed = true;  // since the model was built
  bool shorter_step_logged = false;
  std::vector<double> numbers;     // per variable: Real, Integer, Boolean values
  std::vector<std::string> texts;  // per variable: String values
};

/// A call refused (fmi2Error with the message logged) after which the instance carries on.
struct CallRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Thrown by create_instance to refuse an instantiation (wrong GUID, unreadable resources):
/// fmi2Instantiate logs the message and returns NULL.
struct Refusal : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Defined by each FMU library: its instance for a co-simulation fmi2Instantiate call.
std::unique_ptr<InstanceBase> create_instance(const std::string& instance_name, std::string_view guid,
                                              const ResourceLocation& where, const fmi2CallbackFunctions& cb);

}  // namespace shudder::fmu
