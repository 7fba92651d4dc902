// `shudder diagnose MODEL.toml RUN.csv…`: replay measured runs on the model, find where they
// disagree, name the missing effects, print the summary, write JSON and a report on request.
#include <algorithm>
#include <iostream>
#include <thread>
#include <variant>

#include "analysis/diagnosis.hpp"
#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/diagnosis_inputs.hpp"
#include "io/diagnosis_json.hpp"
#include "io/measured_run.hpp"
#include "io/scenario.hpp"
#include "report/diagnosis_narrative.hpp"
#include "report/diagnosis_report.hpp"
#include "report/diagnosis_summary.hpp"

namespace shudder::app {

int diagnose_command(const DiagnoseOptions& opt) {
  return guarded(opt.model, "diagnosis", [&]() -> int {
    const io::Scenario scenario = io::load_scenario(opt.model);
    const auto model = io::replay_model(scenario);  // refuses kinds measured runs cannot come from
    for (const auto& w : scenario.warnings) std::cerr << "shudder: warning: " << w << "\n";
    scenario.make_clutch();  // fails early, naming the scenario, if the clutch is inconsistent
    std::vector<io::MeasuredRun> runs;
    for (const auto& path : opt.runs) runs.push_back(io::read_measured_run(path));
    io::DiagnosisData data = io::diagnosis_data(runs);
    for (const auto& w : data.warnings) std::cerr << "shudder: warning: " << w << "\n";

    std::vector<std::string> skipped;
    const auto candidates = rig_models::replay_candidates(model, &skipped);
    analysis::DiagnosisOptions o;
    o.jobs = opt.jobs ? opt.jobs : std::max(1u, std::thread::hardware_concurrency());
    o.torque_block_statistics = model.rig;
    o.max_effects = opt.max_effects;
    const auto result = analysis::diagnose(
        data.runs, candidates, rig_models::replay_simulator(model, std::move(data.inputs)), o);

    const std::string text = report::diagnosis_summary(scenario, result, skipped);
    std::cout << text;
    if (!opt.json.empty()) {
      io::write_diagnosis_json(opt.json, result, report::diagnosis_sentences(result));
      std::cout << "JSON: " << opt.json << "\n";
    }
    if (!opt.report.empty()) {
      const report::Report report = report::write_diagnosis_report(opt.report, result, text);
      std::cout << "Report: " << opt.report << " (" << report.files.size() << " files)\n";
      for (const auto& s : report.skipped) std::cerr << "shudder: warning: report: " << s << "\n";
    }
    return 0;
  });
}

}  // namespace shudder::app
