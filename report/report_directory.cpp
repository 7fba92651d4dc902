// Report directories and their index.html; see report_directory.hpp.
#include "report/report_directory.hpp"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "report/text_format.hpp"

namespace shudder::report {

namespace {

namespace fs = std::filesystem;

/// What the text files that report writers put in DIR hold.
std::string file_description(const std::string& name) {
  struct Known {
    const char* file;
    const char* what;
  };
  static constexpr Known kKnown[] = {
      {"summary.txt", "the summary the command printed"},
      {"verdict.json", "the run's shudder verdict block (format shudder-verdict/1, docs/formats/run_output.md)"},
      {"candidates.md", "every candidate effect tried, step by step (docs/formats/diagnosis_json.md)"}};
  for (const auto& k : kKnown)
    if (name == k.file) return k.what;
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".h5" || ext == ".hdf5") return "HDF5 data (docs/formats/)";
  if (ext == ".json") return "JSON data (docs/formats/)";
  if (ext == ".csv") return "CSV data";
  if (ext == ".toml") return "TOML file";
  return "";
}

/// `path` (relative to the working directory or absolute) as seen from `dir`.
std::string relative_to(const std::string& path, const std::string& dir) {
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(fs::absolute(path, ec), ec);
  const fs::path base = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (ec) return path;
  const fs::path rel = target.lexically_relative(base);
  return rel.empty() ? path : rel.generic_string();
}

}  // namespace

void make_report_dir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw io::InputError(dir, 0, "", "cannot create the report directory: " + ec.message());
}

void add_report_plot(Report& report, const std::string& dir, const std::string& file, const Plot& plot) {
  add_report_plot(report, dir, file, single_panel(plot));
}

void add_report_plot(Report& report, const std::string& dir, const std::string& file, const MultiPlot& figure) {
  const std::string path = (fs::path(dir) / file).string();
  try {
    write_multiplot(path, figure);
  } catch (const io::InputError&) {
    throw;
  } catch (const std::exception& e) {
    report.skipped.push_back(file + ": " + e.what());
    return;
  }
  report.files.push_back(path);
  if (!figure.caption.empty()) report.captions[file] = figure.caption;
}

std::vector<std::string> report_data_files(std::initializer_list<std::string> paths) {
  std::vector<std::string> out;
  for (const auto& p : paths)
    if (!p.empty()) out.push_back(p);
  return out;
}

void write_report_index(const std::string& dir, const ReportIndex& index, Report& report) {
  HtmlPage page;
  page.title = index.title;
  page.verdict = index.verdict;
  page.verdict_class = index.verdict_class;
  page.summary = index.summary;
  page.tables = index.tables;
  page.not_drawn = report.skipped;
  for (const auto& f : report.files) {
    const std::string name = fs::path(f).filename().string();
    if (fs::path(name).extension() == ".png" || fs::path(name).extension() == ".svg") {
      const auto caption = report.captions.find(name);
      page.figures.push_back({name, caption == report.captions.end() ? "" : caption->second});
    } else {
      page.files.push_back({name, name, file_description(name)});
    }
  }
  for (const auto& d : index.data_files) page.files.push_back({relative_to(d, dir), d, file_description(d)});
  const std::string path = (fs::path(dir) / "index.html").string();
  io::write_text_file_atomically(path, html_page_text(page));
  report.files.push_back(path);
}

std::pair<std::string, std::string> verdict_line(const std::string& verdict, double frequency_Hz, double amplitude_Nm,
                                                 double onset_time_s) {
  if (verdict == "not_judged") return {"Not judged: the run could not be analysed for shudder.", ""};
  if (verdict == "none") return {"No shudder detected.", "none"};
  std::string s = "Shudder: " + std::string(verdict == "stick-slip" ? "stick-slip" : "friction-induced vibration");
  if (std::isfinite(frequency_Hz)) s += " at " + number(frequency_Hz, "%.4g") + " Hz";
  if (std::isfinite(amplitude_Nm)) s += ", amplitude " + number(amplitude_Nm, "%.3g") + " N m (half peak-to-peak)";
  if (std::isfinite(onset_time_s)) s += ", onset " + number(onset_time_s, "%.3g") + " s";
  return {s + ".", "shudder"};
}

}  // namespace shudder::report
