// `shudder validate`: runs the Paper G / Paper B calibration cases (docs/physics.md §5) listed in
// <scenarios>/validation.toml, checks them against its targets, prints the table and
// regenerates <docs>/validation.md plus PNG plots (report/validation_report). Exit: 0 all
// targets pass, 1 a target fails (the document is still written) or the run failed, 2 bad input.
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/scenario.hpp"
#include "io/validation_targets.hpp"
#include "report/validation_report.hpp"
#include "rig_models/model.hpp"

namespace shudder::app {
namespace {

namespace fs = std::filesystem;

using Run = report::ValidationRun;

}  // namespace

int validate_command(const ValidateOptions& opt) {
  return guarded(opt.scenarios_dir, "validation", [&]() -> int {
    const fs::path docs = opt.docs_dir;
    std::error_code ec;
    fs::create_directories(docs, ec);
    if (ec || !fs::is_directory(docs))
      throw io::InputError(opt.docs_dir, 0, "", "cannot create the docs folder: " + ec.message());

    const io::ValidationSpec spec =
        io::load_validation_spec((fs::path(opt.scenarios_dir) / "validation.toml").string());
    std::vector<Run> runs;
    for (const auto& c : spec.cases) {
      Run r;
      r.label = c.label;
      r.sc = io::load_scenario((fs::path(opt.scenarios_dir) / (c.scenario + ".toml")).string());
      for (const auto& w : r.sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
      r.model = io::visit_kind(r.sc.path, "scenario.type", r.sc.model,
                               [](const auto& m) { return rig_models::validation_model(m); });
      r.rec = rig_models::simulate(r.model, r.sc.make_clutch());
      runs.push_back(std::move(r));
    }
    const std::vector<report::ValidationRow> rows = report::evaluate_targets(spec, runs);
    std::vector<report::Figure> figs;
    try {
      if (opt.plots) figs = report::write_validation_plots(docs, spec, runs);
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const io::InputError*>(&e)) throw;
      throw std::runtime_error(std::string(e.what()) + " (--no-plots skips the plots)");
    }
    report::write_validation_doc(docs, spec, runs, rows, figs, opt.plots);

    report::print_validation_table(std::cout, rows);
    std::size_t failed = 0;
    for (const auto& r : rows) failed += r.pass == "NO";
    std::cout << "\n"
              << (failed ? std::to_string(failed) + " target(s) FAIL" : std::string("All targets pass")) << "; wrote "
              << (docs / "validation.md").string();
    if (opt.plots) std::cout << " and " << figs.size() << " plots";
    std::cout << "\n";
    return failed ? 1 : 0;
  });
}

}  // namespace shudder::app
