// Report directories of `run` and `sweep`; see run_report_directory.hpp.
#include "report/run_report_directory.hpp"

#include <cmath>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/verdict_json.hpp"
#include "report/plots.hpp"
#include "report/text_format.hpp"
#include "studies/run_verdict.hpp"

namespace shudder::report {

namespace {

namespace fs = std::filesystem;

std::string value_text(double v) { return std::isfinite(v) ? number(v, "%.4g") : "–"; }

std::string units_text(const std::string& units) {
  if (units == "degC") return "°C";
  if (units == "1") return "";
  return units;
}

double scalar_or_nan(const dynamics::ResultBlock& b, const char* name) {
  const dynamics::Scalar* s = b.find_scalar(name);
  return s ? s->value : NAN;
}

/// The sweep's /cases: one row per case, the swept keys and results, then the verdict and message.
HtmlTable cases_table(const io::SweepTable& table) {
  HtmlTable t;
  t.caption = "Cases";
  for (const auto& c : table.columns) {
    const std::string units = units_text(c.units);
    t.header.push_back(c.name + (units.empty() ? "" : " [" + units + "]"));
  }
  if (!table.text_column.empty()) t.header.push_back(table.text_column_name);
  const bool messages = !table.message_column.empty();
  if (messages) t.header.push_back("message");
  const std::size_t n = table.columns.empty() ? table.text_column.size() : table.columns.front().values.size();
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<std::string> row;
    for (const auto& c : table.columns) row.push_back(k < c.values.size() ? value_text(c.values[k]) : "");
    if (!table.text_column.empty()) row.push_back(k < table.text_column.size() ? table.text_column[k] : "");
    if (messages) row.push_back(k < table.message_column.size() ? table.message_column[k] : "");
    t.rows.push_back(std::move(row));
  }
  return t;
}

}  // namespace

HtmlTable verdict_table(const dynamics::ResultBlock& verdict) {
  HtmlTable t;
  t.caption = "Verdict block";
  t.header = {"quantity", "value", "units"};
  for (const auto& text : verdict.texts) t.rows.push_back({text.name, text.value, ""});
  for (const auto& s : verdict.scalars) t.rows.push_back({s.name, value_text(s.value), units_text(s.units)});
  return t;
}

Report write_run_report(const std::string& dir, const dynamics::Recording& rec, const std::string& name,
                        const std::string& summary, bool rig, const std::string& run_file) {
  make_report_dir(dir);
  Report report;
  const auto path = [&](const char* f) { return (fs::path(dir) / f).string(); };
  io::write_text_file_atomically(path("summary.txt"), summary);
  report.files.push_back(path("summary.txt"));
  ReportIndex index;
  index.title = "shudder run: " + name;
  index.summary = summary;
  index.data_files = {run_file};
  if (const auto* verdict = rec.find_block(studies::kVerdictBlock)) {
    io::write_verdict_json(*verdict, path("verdict.json"));
    report.files.push_back(path("verdict.json"));
    const auto* text = verdict->find_text("verdict");
    std::tie(index.verdict, index.verdict_class) =
        verdict_line(text ? text->value : "not_judged", scalar_or_nan(*verdict, "frequency_Hz"),
                     scalar_or_nan(*verdict, "amplitude_Nm"), scalar_or_nan(*verdict, "onset_time_s"));
    if (const auto* reason = verdict->find_text("reason")) index.verdict += " " + reason->value;
    index.tables.push_back(verdict_table(*verdict));
  }
  struct Item {
    PlotKind kind;
    const char* file;
    bool wanted;
  };
  // A driveline run has no torque cell: its coupling takes the torque plot's place.
  const bool driveline = rec.find("coupling_torque_Nm") != nullptr;
  const Item items[] = {{PlotKind::kTorque, "torque.png", !driveline},
                        {PlotKind::kCoupling, "coupling.png", driveline},
                        {PlotKind::kTemperature, "temperature.png", true},
                        {PlotKind::kSpectrum, "spectrum.png", !driveline},
                        {PlotKind::kSpectrogram, "spectrogram.png", rig},
                        {PlotKind::kStabilityMap, "stability_map.png", rig && rec.find_map("stability_map")}};
  for (const auto& item : items) {
    if (!item.wanted) continue;
    MultiPlot plot;
    try {
      plot = run_plot(item.kind, rec, name, "the run");
    } catch (const io::InputError& e) {
      report.skipped.push_back(std::string(item.file) + ": " + e.what());
      continue;
    }
    add_report_plot(report, dir, item.file, plot);  // a gnuplot failure skips the plot, as elsewhere
  }
  write_report_index(dir, index, report);
  return report;
}

Report write_sweep_report(const std::string& dir, const io::SweepTable& table, const std::string& name,
                          const std::string& summary, const std::string& sweep_file) {
  make_report_dir(dir);
  Report report;
  const std::string summary_path = (fs::path(dir) / "summary.txt").string();
  io::write_text_file_atomically(summary_path, summary);
  report.files.push_back(summary_path);
  add_report_plot(report, dir, "sweep.png", sweep_plot(table, name, "the sweep"));
  ReportIndex index;
  index.title = "shudder sweep: " + name;
  index.summary = summary;
  index.tables.push_back(cases_table(table));
  index.data_files = {sweep_file};
  write_report_index(dir, index, report);
  return report;
}

}  // namespace shudder::report
