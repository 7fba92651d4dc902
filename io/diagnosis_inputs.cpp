#include "io/diagnosis_inputs.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <variant>

#include "dynamics/signal_names.hpp"
#include "io/input_error.hpp"
#include "studies/model_studies.hpp"
#include "io/kind_refusal.hpp"
#include "rig_models/coupling_measurement.hpp"
#include "rig_models/rig_names.hpp"

namespace shudder::io {

studies::ReplayModel replay_model(const Scenario& s) {
  studies::ReplayModel m = visit_kind(s.path, "scenario.type", s.model, [&](const auto& kind_model) {
    return studies::replay_model(kind_model, s.stick_time);
  });
  m.clutch = s.clutch;
  m.fluid = s.fluid;
  return m;
}

namespace {

DiagnosisData read_runs(const std::vector<MeasuredRun>& runs) {
  DiagnosisData d;
  std::string rig_source;
  for (const auto& run : runs) {
    if (const auto rig = run.meta("rig"); rig && !rig->empty()) {
      if (d.rig.empty()) {
        d.rig = *rig;
        rig_source = run.path;
      } else if (*rig != d.rig) {
        throw InputError(run.path, 0, "rig",
                         "this run comes from rig '" + *rig + "' but " + rig_source + " from rig '" + d.rig +
                             "'; diagnose runs of one rig at a time");
      }
    }
    if (run.rows() < diagnosis_min_rows || run.duration_s() < diagnosis_min_duration_s) {
      char what[200];
      std::snprintf(what, sizeof what,
                    "the run has %zu rows over %.6g s; the diagnosis needs at least %zu rows and %.6g s to fit "
                    "parameters and hold some data out",
                    static_cast<std::size_t>(run.rows()), run.duration_s(),
                    static_cast<std::size_t>(diagnosis_min_rows), diagnosis_min_duration_s);
      throw InputError(run.path, 0, "", what);
    }

    analysis::DiagnosisRun dr;
    dr.name = std::filesystem::path(run.path).filename().string();
    namespace sn = dynamics::signal_names;
    dr.time_s = run.required(sn::kTime);
    dr.speed_rpm = run.required(sn::kSpeed);
    dr.normal_force_N = run.required(sn::kNormalForce);
    dr.torque_Nm = run.required(sn::kTorque);
    dr.temp_C = run.required(sn::kTemp);
    if (const auto* c = run.column(sn::kSumpTemp)) dr.sump_temp_C = *c;
    if (const auto* c = run.column(sn::kIrTemp)) dr.ir_temp_C = *c;

    studies::ReplayInputs in;
    in.time_s = dr.time_s;
    in.speed_rpm = dr.speed_rpm;
    in.normal_force_N = dr.normal_force_N;
    in.temp_C = dr.temp_C;
    in.torque_Nm = dr.torque_Nm;
    in.sump_temp_C = dr.sump_temp_C;
    if (const auto flow = run.meta("oil_flow_ml_min")) {
      char* end = nullptr;
      const double v = std::strtod(flow->c_str(), &end);
      if (end == flow->c_str() || *end != '\0' || !std::isfinite(v) || v < 0)
        throw InputError(run.path, 0, "oil_flow_ml_min", "'" + *flow + "' is not a flow; give a number >= 0 (ml/min)");
      in.oil_flow_ml_min = v;
    }
    if (const auto sensor = run.meta("temp_sensor")) {
      try {
        studies::parse_temp_sensor(*sensor, in);
      } catch (const std::exception&) {
        throw InputError(run.path, 0, "temp_sensor", "'" + *sensor + "' has an r_mm or z_mm that is not a number");
      }
      if (!in.thermocouple_r_mm && !in.thermocouple_z_mm)
        d.warnings.push_back(run.path + ": temp_sensor '" + *sensor +
                             "' names no position (r_mm=…, z_mm=…); the model's thermocouple is used");
    }
    // Names must tell runs apart in the result; fall back to the path when two share a name.
    for (const auto& other : d.runs)
      if (other.name == dr.name) dr.name = run.path;
    d.runs.push_back(std::move(dr));
    d.inputs.push_back(std::move(in));
  }
  return d;
}

}  // namespace

DiagnosisData diagnosis_data(const std::vector<MeasuredRun>& runs) {
  studies::ReplayModel lsctr;
  return diagnosis_data(runs, lsctr);
}

DiagnosisData diagnosis_data(const std::vector<MeasuredRun>& runs, const studies::ReplayModel& model) {
  DiagnosisData d = read_runs(runs);
  if (d.rig.empty()) return d;
  if (d.rig == model.rig) return d;
  if (model.rig == rig_models::kCouplingRig)
    d.warnings.push_back("the runs come from rig '" + d.rig + "'; the model is a driveline's Haldex coupling ('" +
                         model.rig + "')");
  else if (model.rig == rig_models::kNetworkClutchRig)
    d.warnings.push_back("the runs come from rig '" + d.rig + "'; the model is a network's clutch ('" + model.rig +
                         "')");
  else
    d.warnings.push_back("the runs come from rig '" + d.rig + "'; the model is of the LSCTR");
  return d;
}

}  // namespace shudder::io
