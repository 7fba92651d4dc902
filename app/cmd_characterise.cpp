// `shudder characterise RUN... -o FLUID.toml`: measured speed ramps -> a fluid file
// (docs/characterisation.md). Parsing, file checks and printing only: the ramps, compensation
// and fits are analysis::characterise; the files come from io/characterisation_output.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "analysis/breakaway.hpp"
#include "analysis/friction_characterisation.hpp"
#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "clutch/friction_radius.hpp"
#include "io/atomic_file.hpp"
#include "io/characterisation_output.hpp"
#include "io/diagnosis_inputs.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"
#include "io/measured_run.hpp"
#include "io/import_plausibility.hpp"
#include "io/logger_import.hpp"
#include "io/output_safety.hpp"
#include "io/scenario.hpp"
#include "report/characterisation_report.hpp"
#include "studies/inverse_characterisation.hpp"

namespace shudder::app {

namespace {

// "40,80,120" -> {40, 80, 120}; InputError naming `option` otherwise.
std::vector<double> parse_list(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (!text.empty()) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(x))
      throw io::InputError(option, 0, "", "'" + item + "' is not a number; give numbers separated by commas");
    out.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

analysis::RampRun to_ramp_run(const io::MeasuredRun& m, const std::string& temp_channel) {
  const std::vector<double>* temp = m.column(temp_channel);
  if (!temp)
    throw io::InputError(
        m.path, 0, "",
        "has no column '" + temp_channel +
            "' (--temperature-channel); its columns "
            "are those of docs/formats/measured_run.md: temp_C always, ir_temp_C when the rig logged it");
  return {m.path, m.required("time_s"), m.required("speed_rpm"), m.required("normal_force_N"), m.required("torque_Nm"),
          *temp};
}

// A run's annulus radius from its metadata (`inner_radius_mm`, `outer_radius_mm`), if given.
std::optional<double> metadata_radius_mm(const io::MeasuredRun& m, const std::string& key) {
  const auto text = m.meta(key);
  if (!text) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(text->c_str(), &end);
  if (end == text->c_str() || *end != '\0' || !(x > 0) || !std::isfinite(x))
    throw io::InputError(m.path, 0, key,
                         "is '" + *text + "'; give the friction annulus radius in mm (a positive number)");
  return x;
}

// --radius model (the default): the radius at which the clutch model the fluid is for produces
// torque (clutch/friction_radius.hpp): the clutch of --model, else the default clutch on the
// annulus of the run's metadata (inner_radius_mm, outer_radius_mm) or of --inner/--outer-radius-mm.
void set_model_radius(analysis::FrictionConversion& c, const std::optional<io::Scenario>& scenario,
                      const io::MeasuredRun& first, const CharacteriseOptions& o) {
  clutch::ThermalParams thermal;
  std::string where;
  if (scenario) {
    thermal = scenario->clutch.thermal;
    where = "the clutch of " + o.model;
  } else {
    const auto ri = metadata_radius_mm(first, "inner_radius_mm"), ro = metadata_radius_mm(first, "outer_radius_mm");
    thermal.inner_radius_m = ri.value_or(o.inner_radius_mm) * 1e-3;
    thermal.outer_radius_m = ro.value_or(o.outer_radius_mm) * 1e-3;
    if (!(thermal.outer_radius_m > thermal.inner_radius_m))
      throw io::InputError(ri || ro ? first.path : "--inner-radius-mm/--outer-radius-mm", 0,
                           ri || ro ? "outer_radius_mm" : "", "the outer radius must exceed the inner");
    where = std::string("the default clutch on ") + (ri || ro ? "the run's annulus " : "the annulus ");
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4g-%.4g mm", thermal.inner_radius_m * 1e3, thermal.outer_radius_m * 1e3);
    where += buf;
  }
  c.inner_radius_mm = thermal.inner_radius_m * 1e3;
  c.outer_radius_mm = thermal.outer_radius_m * 1e3;
  c.model_radius_mm = clutch::model_friction_radius_m(thermal) * 1e3;
  c.source = "the model's radius, uniform pressure on its rings, " + where;
}

// Paths distinct, output directories there, viscosities usable: before anything is read.
void check_command_line(const CharacteriseOptions& o) {
  if (o.runs.empty()) throw io::InputError("characterise", 0, "", "no measured run given");
  std::vector<io::RolePath> inputs, outputs{{"-o", o.output}};
  for (const auto& r : o.runs) inputs.push_back({"measured run", r});
  if (!o.json.empty()) outputs.push_back({"--json", o.json});
  io::require_distinct_paths(inputs, outputs);
  for (const auto& out : outputs) io::require_output_directory(out.path);
  if (!(o.nu40_cSt > o.nu100_cSt) || !(o.nu100_cSt > 0))
    throw io::InputError("--nu40-cSt/--nu100-cSt", 0, "",
                         "give the fluid's kinematic viscosities with nu40 > nu100 > 0 cSt (Walther needs both)");
  if (!(o.outer_radius_mm > o.inner_radius_mm))
    throw io::InputError("--inner-radius-mm/--outer-radius-mm", 0, "", "the outer radius must exceed the inner");
}

// The fit's settings from the options (CLI11 has checked the choices' spelling).
analysis::CharacterisationSettings settings_of(const CharacteriseOptions& o) {
  analysis::CharacterisationSettings s;
  s.law = o.law == "linear"  ? analysis::LawKind::kLinear
          : o.law == "table" ? analysis::LawKind::kTable
                             : analysis::LawKind::kMaki;
  s.compensation = o.compensation == "none"        ? analysis::Compensation::kNone
                   : o.compensation == "linear"    ? analysis::Compensation::kLinear
                   : o.compensation == "piecewise" ? analysis::Compensation::kPiecewise
                                                   : analysis::Compensation::kQuadratic;
  if (std::isfinite(o.alpha_per_C)) s.alpha_per_C = o.alpha_per_C;
  s.conversion.rule = o.radius == "uniform_pressure" ? analysis::RadiusRule::kUniformPressure
                      : o.radius == "uniform_wear"   ? analysis::RadiusRule::kUniformWear
                                                     : analysis::RadiusRule::kModel;
  s.conversion.mean_radius_mm = o.mean_radius_mm;
  s.conversion.inner_radius_mm = o.inner_radius_mm;
  s.conversion.outer_radius_mm = o.outer_radius_mm;
  s.conversion.interfaces = o.interfaces;
  s.conversion.bearing_drag_mu = o.bearing_drag_mu;
  s.temp_tolerance_C = o.temp_tolerance_C;
  s.min_ramps_per_row = o.min_ramps;
  s.linear_load_N = o.linear_load_N;
  s.row_temps_C = parse_list("--row-temps", o.row_temps);
  s.node_rpm = parse_list("--node-rpm", o.node_rpm);
  s.hot_row = o.hot_row;
  return s;
}

// The model the fluid is for (--model): its clutch's friction radius, and the replay of
// --method inverse. It must be the clutch the runs measured.
std::optional<io::Scenario> model_of(const CharacteriseOptions& o) {
  if (o.model.empty()) return std::nullopt;
  io::Scenario scenario = io::load_scenario(o.model);
  if (scenario.clutch.sliding_interfaces != o.interfaces)
    throw io::InputError(o.model, 0, "clutch.sliding_interfaces",
                         "is " + std::to_string(scenario.clutch.sliding_interfaces) + " but --interfaces is " +
                             std::to_string(o.interfaces) + "; the model must be the clutch the runs measured");
  return scenario;
}

struct ReadRuns {
  std::vector<io::MeasuredRun> measured;  // as read (their metadata and every column)
  std::vector<analysis::RampRun> ramps;   // the columns the fit reads
};

// Every run, as a measured run or through the logger import (--map/--mapping); the runs must
// come from one rig.
ReadRuns read_runs(const CharacteriseOptions& o) {
  ReadRuns r;
  std::string rig, rig_file;
  io::ImportSpec logger = io::import_spec_of(o.maps, o.mapping);
  logger.trust_units = logger.trust_units || o.trust_units;
  std::vector<std::string> import_warnings;
  for (const auto& path : o.runs) {
    const io::MeasuredRun& m = r.measured.emplace_back(io::read_measured_or_logger(path, logger, import_warnings));
    if (!logger.trust_units) io::check_measured_run_units(m);  // kN, ms or K in a measured run: one line naming the fix
    const std::string this_rig = m.meta("rig").value_or("");
    if (r.ramps.empty()) {
      rig = this_rig;
      rig_file = path;
    } else if (this_rig != rig) {
      throw io::InputError(path, 0, "rig",
                           "is '" + this_rig + "' but " + rig_file + " is '" + rig +
                               "'; characterise one rig's runs at a time (friction radius and "
                               "interfaces differ between rigs)");
    }
    r.ramps.push_back(to_ramp_run(m, o.temperature_channel));
  }
  for (const auto& w : import_warnings) std::cerr << "shudder: warning: " << w << "\n";
  return r;
}

analysis::Characterisation fit_from_sensors(const ReadRuns& runs, const analysis::CharacterisationSettings& s) {
  try {
    return analysis::characterise(runs.ramps, s);
  } catch (const analysis::CharacterisationInputError& e) {
    throw io::InputError(e.file(), 0, "", e.what());
  }
}

// --method inverse: the same settings, replayed through the clutch and thermal model (of
// --model, else the default clutch on the conversion's annulus); its law is the one written.
studies::InverseCharacterisation fit_inverse(const ReadRuns& runs, const analysis::CharacterisationSettings& s,
                                             const std::optional<io::Scenario>& scenario,
                                             const CharacteriseOptions& o) {
  studies::InverseSettings is;
  if (scenario) {
    is.model = io::replay_model(*scenario);
  } else {
    is.model.clutch.sliding_interfaces = o.interfaces;
    is.model.fluid.nu40_cSt = o.nu40_cSt;
    is.model.fluid.nu100_cSt = o.nu100_cSt;
    is.model.settings.thermal_step_s = 0.02;                  // the ramps last seconds; 20 ms resolves the heating
    if (s.conversion.rule == analysis::RadiusRule::kModel) {  // the annulus the radius was taken from
      is.model.clutch.thermal.inner_radius_m = s.conversion.inner_radius_mm * 1e-3;
      is.model.clutch.thermal.outer_radius_m = s.conversion.outer_radius_mm * 1e-3;
    }
  }
  is.jobs = std::max(1u, std::thread::hardware_concurrency());
  is.max_iterations = o.inverse_iterations;
  const io::DiagnosisData data = io::diagnosis_data(runs.measured);
  studies::InverseCharacterisation inverse;
  try {
    inverse = studies::characterise_inverse(runs.ramps, data.inputs, s, o.temperature_channel, is);
  } catch (const analysis::CharacterisationInputError& e) {
    throw io::InputError(e.file(), 0, "", e.what());
  }
  // Where the inverse method should not be used (docs/characterisation.md 2c).
  auto& warnings = inverse.inverse.warnings;
  if (s.compensation == analysis::Compensation::kNone)
    warnings.push_back(
        "--method inverse with --compensation none: no temperature enters the law, so it equals "
        "the sensor method's (at many times the cost)");
  else if (!s.hot_row && inverse.inverse.max_temp_C > inverse.inverse.temps_C.back() + s.temp_tolerance_C)
    warnings.push_back(
        "--method inverse with --no-hot-row on runs that heat above the top row: its compensation "
        "takes out more of the heating than the sensor method's and nothing puts it back, so it "
        "replays worse; drop --no-hot-row");
  return inverse;
}

// The fluid's name, viscosities and breakaway ratio: given, else measured from the runs'
// starts from rest against the written law.
io::FluidIdentity identity_of(const CharacteriseOptions& o, const analysis::BreakawayMeasurement& breakaway) {
  io::FluidIdentity id;
  id.name = o.name.empty() ? std::filesystem::path(o.output).stem().string() : o.name;
  id.description = "characterised by shudder from " + std::to_string(o.runs.size()) + " measured run(s)";
  id.nu40_cSt = o.nu40_cSt;
  id.nu100_cSt = o.nu100_cSt;
  if (std::isfinite(o.breakaway_ratio)) {
    id.breakaway_ratio = o.breakaway_ratio;
    id.breakaway_source = "given on the command line (--breakaway-ratio)";
  } else if (breakaway.ratio) {
    id.breakaway_ratio = *breakaway.ratio;
    id.breakaway_source = "measured: median peak/kinetic friction over " + std::to_string(breakaway.events.size()) +
                          " start(s) from rest (" + report::breakaway_range(breakaway) + ")";
  } else {
    id.breakaway_ratio = 1.0;
    id.breakaway_source = "not measured: " + breakaway.not_measured + "; mu_s = mu_k(v_min) assumed";
  }
  return id;
}

}  // namespace

int characterise_command(const CharacteriseOptions& o) {
  return guarded(o.output, "characterise", [&] {
    check_command_line(o);
    analysis::CharacterisationSettings s = settings_of(o);
    const std::optional<io::Scenario> scenario = model_of(o);
    const ReadRuns runs = read_runs(o);
    if (s.conversion.rule == analysis::RadiusRule::kModel)
      set_model_radius(s.conversion, scenario, runs.measured.front(), o);

    // The law: from the sensors, or (--method inverse) replayed through the model, the sensor
    // fit reported beside it.
    analysis::Characterisation c = fit_from_sensors(runs, s);
    std::optional<studies::InverseCharacterisation> inverse;
    analysis::CharacterisationSettings written = s;
    if (o.method == "inverse") {
      inverse = fit_inverse(runs, s, scenario, o);
      c = inverse->inverse;
      written = inverse->settings;
    }

    const analysis::BreakawayMeasurement breakaway = analysis::measure_breakaway(runs.ramps, s.conversion, *c.law);
    const io::FluidIdentity id = identity_of(o, breakaway);
    const std::string toml = io::characterised_fluid_toml(c, written, id, o.runs);
    // The file must load as every command loads it; a failure here is ours (exit 1).
    try {
      io::load_fluid_text(toml, o.output);
    } catch (const io::InputError& e) {
      throw std::runtime_error(std::string("the fitted fluid file would not load: ") + e.what());
    }

    // Summary, JSON and report; every file written whole or not at all.
    const std::string summary = report::characterisation_summary(c, written, o.output) +
                                (inverse ? report::method_comparison_summary(*inverse, s) : std::string()) +
                                report::breakaway_summary(breakaway, id.breakaway_ratio, id.breakaway_source);
    const std::string json =
        o.json.empty() ? ""
                       : io::with_breakaway_json(inverse ? io::characterisation_json(*inverse, s, o.runs, o.output)
                                                         : io::characterisation_json(c, s, o.runs, o.output),
                                                 breakaway, id.breakaway_ratio, id.breakaway_source);
    if (!o.report.empty()) {
      const report::Report rep =
          report::write_characterisation_report(o.report, c, summary, report::report_data_files({o.output, o.json}));
      for (const auto& why : rep.skipped) std::cerr << "shudder: note: report: skipped " << why << "\n";
    }
    io::write_text_file_atomically(o.output, toml);
    if (!o.json.empty()) io::write_text_file_atomically(o.json, json);
    for (const auto& w : c.warnings) std::cerr << "shudder: warning: " << w << "\n";
    std::cout << summary;
    return 0;
  });
}

}  // namespace shudder::app
