// `shudder diagnose MODEL.toml RUN.csv…`: replay measured runs on the model, find where they
// disagree, name the missing effects, print the summary, write JSON and a report on request.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <optional>
#include <iostream>
#include <thread>
#include <variant>

#include "analysis/diagnosis.hpp"
#include "studies/clutch_replay.hpp"
#include "components/network_builder.hpp"
#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/diagnosis_inputs.hpp"
#include "io/diagnosis_json.hpp"
#include "io/diagnosis_plausibility.hpp"
#include "io/fixed_model.hpp"
#include "io/input_error.hpp"
#include "io/logger_import.hpp"
#include "io/measured_run.hpp"
#include "io/network_scenario.hpp"
#include "io/scenario.hpp"
#include "report/diagnosis_narrative.hpp"
#include "report/diagnosis_report.hpp"
#include "report/diagnosis_summary.hpp"
#include "studies/law_data_check.hpp"

namespace shudder::app {

namespace {

// "torque_Nm=0.5,temp_C=2" -> {{"torque_Nm", 0.5}, {"temp_C", 2}}; InputError (exit 2) for an
// unknown channel, a value that is not a number >= 0, or a channel given twice.
std::vector<std::pair<std::string, double>> parse_tolerance(const std::string& text) {
  static const char* const kChannels[] = {"torque_Nm", "temp_C", "sump_temp_C", "ir_temp_C", "temp_minus_ir_C"};
  const std::string allowed =
      "give CHANNEL=VALUE[,CHANNEL=VALUE…] with CHANNEL one of torque_Nm, temp_C, "
      "sump_temp_C, ir_temp_C, temp_minus_ir_C and VALUE >= 0 in the channel's unit";
  std::vector<std::pair<std::string, double>> out;
  std::size_t pos = 0;
  while (!text.empty() && pos <= text.size()) {
    const std::size_t comma = std::min(text.find(',', pos), text.size());
    const std::string item = text.substr(pos, comma - pos);
    const std::size_t eq = item.find('=');
    const std::string name = item.substr(0, eq);
    bool known = false;
    for (const char* c : kChannels) known = known || name == c;
    if (eq == std::string::npos || !known)
      throw io::InputError("--tolerance", 0, "", "'" + item + "' is not a channel tolerance; " + allowed);
    const std::string value = item.substr(eq + 1);
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v) || v < 0)
      throw io::InputError("--tolerance", 0, name, "'" + value + "' is not a tolerance; " + allowed);
    for (const auto& [n, x] : out)
      if (n == name) throw io::InputError("--tolerance", 0, name, "given twice; " + allowed);
    out.emplace_back(name, v);
    pos = comma + 1;
  }
  return out;
}

// The model the runs are replayed on, however the scenario describes it.
struct Baseline {
  studies::ReplayModel model;
  report::DiagnosisSubject subject;
  std::function<void(const std::vector<analysis::FittedEffect>&, const std::string&)> write_fixed;
};

// A network scenario: the clutch named by --clutch, else by the runs' `clutch` metadata, else the
// network's only wet clutch (studies/clutch_replay.hpp).
Baseline network_baseline(const DiagnoseOptions& opt, const std::vector<io::MeasuredRun>& runs) {
  auto sc = std::make_shared<const io::NetworkScenario>(io::load_network_scenario(opt.model));
  for (const auto& w : sc->warnings) std::cerr << "shudder: warning: " << w << "\n";
  const std::vector<std::string> wet = studies::wet_clutch_names(sc->spec);
  std::string clutch = opt.clutch, key = "--clutch";
  if (clutch.empty())
    for (const auto& run : runs)
      if (const auto c = run.meta("clutch"); c && !c->empty()) {
        if (!clutch.empty() && *c != clutch)
          throw io::InputError(run.path, 0, "clutch",
                               "this run is of clutch '" + *c + "', another of '" + clutch +
                                   "'; diagnose one clutch's runs at a time, or name it with --clutch");
        clutch = *c;
        key = "clutch (the runs' metadata)";
      }
  if (clutch.empty()) {
    if (wet.size() != 1) {
      std::string list;
      for (const auto& n : wet) list += (list.empty() ? "" : ", ") + n;
      throw io::InputError(opt.model, 0, "--clutch",
                           wet.empty() ? "the network has no wet clutch: a measured run is of a wet clutch"
                                       : "the network has " + std::to_string(wet.size()) +
                                             " wet clutches and the runs do not say which they are of; name "
                                             "one with --clutch (" +
                                             list + ")");
    }
    clutch = wet.front();
  }
  Baseline b;
  try {
    b.model = studies::clutch_replay_model(sc->spec, clutch);
  } catch (const components::NetworkError& e) {
    throw io::InputError(opt.model, 0, key, e.what());
  }
  const components::ClutchSpec* spec = nullptr;
  for (const auto& c : sc->spec.clutches)
    if (c.name == clutch) spec = &c;
  b.subject = {opt.model, "network clutch '" + clutch + "'", spec->wet.enabled_effects};
  b.write_fixed = [sc, clutch](const std::vector<analysis::FittedEffect>& effects, const std::string& out) {
    io::write_fixed_network(*sc, clutch, effects, out);
  };
  return b;
}

Baseline scenario_baseline(const DiagnoseOptions& opt) {
  auto scenario = std::make_shared<const io::Scenario>(io::load_scenario(opt.model));
  Baseline b;
  b.model = io::replay_model(*scenario);  // refuses kinds measured runs cannot come from
  for (const auto& w : scenario->warnings) std::cerr << "shudder: warning: " << w << "\n";
  scenario->make_clutch();  // fails early, naming the scenario, if the clutch is inconsistent
  b.subject = report::diagnosis_subject(*scenario);
  b.write_fixed = [scenario](const std::vector<analysis::FittedEffect>& effects, const std::string& out) {
    io::write_fixed_model(*scenario, effects, out);
  };
  return b;
}

}  // namespace

int diagnose_command(const DiagnoseOptions& opt) {
  return guarded(opt.model, "diagnosis", [&]() -> int {
    const auto tolerance = parse_tolerance(opt.tolerance);
    const bool network = io::scenario_type(opt.model) == "network";
    std::optional<Baseline> baseline;
    if (!network) baseline = scenario_baseline(opt);
    if (!network && !opt.clutch.empty())
      throw io::InputError(opt.model, 0, "--clutch",
                           "names a clutch of a network scenario; this scenario has one clutch "
                           "(remove --clutch)");
    std::vector<io::MeasuredRun> runs;
    io::ImportSpec logger = io::import_spec_of(opt.maps, opt.mapping);  // --map/--mapping: logger files
    logger.trust_units = logger.trust_units || opt.trust_units;
    std::vector<std::string> import_warnings;
    for (const auto& path : opt.runs) runs.push_back(io::read_measured_or_logger(path, logger, import_warnings));
    for (const auto& w : import_warnings) std::cerr << "shudder: warning: " << w << "\n";
    if (network) baseline = network_baseline(opt, runs);
    const studies::ReplayModel& model = baseline->model;
    io::DiagnosisData data = io::diagnosis_data(runs, model);
    const analysis::DiagnosisOptions defaults;
    io::check_plausibility(runs, model, defaults.statistics_block_s, data.warnings);
    for (const auto& w : data.warnings) std::cerr << "shudder: warning: " << w << "\n";

    // A gap the law's own data range explains (studies/law_data_check.hpp).
    for (const auto& w : studies::law_above_its_data(model, data.inputs, opt.runs))
      std::cerr << "shudder: warning: " << w << "\n";

    std::vector<std::string> skipped;
    const auto candidates = studies::replay_candidates(model, &skipped);
    analysis::DiagnosisOptions o;
    o.jobs = opt.jobs ? opt.jobs : std::max(1u, std::thread::hardware_concurrency());
    o.torque_block_statistics = model.kind == ModelKind::kRig;
    o.max_effects = opt.max_effects;
    o.tolerance = tolerance;
    const auto reproduce = studies::replay_reproducer(model, data.inputs);
    const auto result = analysis::diagnose(data.runs, candidates,
                                           studies::replay_simulator(model, std::move(data.inputs)), o, reproduce);
    for (const auto& w : result.warnings) std::cerr << "shudder: warning: " << w << "\n";

    const std::string text = report::diagnosis_summary(baseline->subject, result, skipped);
    std::cout << text;
    if (!opt.json.empty()) {
      io::write_diagnosis_json(opt.json, result, report::diagnosis_sentences(result));
      std::cout << "JSON: " << opt.json << "\n";
    }
    if (!opt.write_model.empty()) {
      baseline->write_fixed(result.final_effects, opt.write_model);
      std::cout << "Model: " << opt.write_model << "\n";
    }
    if (!opt.report.empty()) {
      const report::Report report = report::write_diagnosis_report(
          opt.report, result, text, report::report_data_files({opt.json, opt.write_model}));
      std::cout << "Report: " << opt.report << " (" << report.files.size() << " files)\n";
      for (const auto& s : report.skipped) std::cerr << "shudder: warning: report: " << s << "\n";
    }
    return 0;
  });
}

}  // namespace shudder::app
