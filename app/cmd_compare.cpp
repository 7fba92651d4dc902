// `shudder compare FLUID...`: anti-shudder indices, equal-viscosity indices, breakaway ratio,
// stability margins and a ranking of several fluids (docs/characterisation.md). Parsing and
// printing only: studies::compare_fluids computes, report/comparison_report words and draws.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/atomic_file.hpp"
#include "io/comparison_json.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/output_safety.hpp"
#include "io/scenario.hpp"
#include "report/comparison_report.hpp"
#include "studies/fluid_comparison.hpp"

namespace shudder::app {

namespace {

std::vector<double> parse_temps(const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0' || !std::isfinite(x) || x < -273.15 || x > 1000.0)
      throw io::InputError("--temps", 0, "",
                           "'" + item + "' is not a temperature; give degC separated by commas, e.g. 30,60,90");
    out.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

int compare_command(const CompareOptions& o) {
  return guarded(o.fluids.empty() ? "compare" : o.fluids.front(), "comparison", [&] {
    std::vector<io::RolePath> inputs, outputs;
    for (const auto& f : o.fluids) inputs.push_back({"fluid file", f});
    for (const auto& r : o.rigs) inputs.push_back({"rig scenario", r});
    if (!o.json.empty()) outputs.push_back({"--json", o.json});
    io::require_distinct_paths(inputs, outputs);
    for (const auto& out : outputs) io::require_output_directory(out.path);
    if (!(o.load_N > 0) || !std::isfinite(o.load_N))
      throw io::InputError("--load-N", 0, "", "must be a finite normal force > 0 N, e.g. 20000");

    std::vector<std::pair<std::string, clutch::Fluid>> fluids;
    for (const auto& f : o.fluids) {
      if (std::error_code ec; !std::filesystem::is_regular_file(f, ec))
        throw io::InputError(f, 0, "", "no such fluid file; give fluid TOML files (docs/formats/fluid_file.md)");
      fluids.emplace_back(f, io::load_fluid(f));
    }
    studies::ComparisonOptions co;
    co.screening.indices.load_N = o.load_N;
    co.viscosity_cSt = o.viscosity_cSt;
    if (!o.temps.empty()) co.screening.temps_C = parse_temps(o.temps);
    for (const auto& path : o.rigs) {
      const io::Scenario sc = io::load_scenario(path);
      studies::ScreeningRig rig;
      rig.label = sc.name;
      rig.params = io::visit_kind(path, "scenario.type", sc.model, [](const auto& m) -> const rig_models::RigParams& {
        return rig_models::screening_rig(m);
      });
      rig.clutch = sc.clutch;
      co.screening.rigs.push_back(rig);
    }
    const studies::Comparison c = studies::compare_fluids(fluids, co);
    const std::string summary = report::comparison_summary(c);
    if (!o.report.empty()) {
      const report::Report rep =
          report::write_comparison_report(o.report, c, fluids, summary, report::report_data_files({o.json}));
      for (const auto& why : rep.skipped) std::cerr << "shudder: note: report: skipped " << why << "\n";
    }
    if (!o.json.empty()) io::write_text_file_atomically(o.json, io::comparison_json(c));
    std::cout << summary;
    return 0;
  });
}

}  // namespace shudder::app
