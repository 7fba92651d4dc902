#pragma once
// The report directories of `run`, `sweep`, `diagnose`, `characterise` and `compare --report
// DIR` (docs/plots.md): what a writer puts there, and the index.html that ties it together.
// A writer creates the directory (make_report_dir), writes its text files and plots
// (add_report_plot: a plot gnuplot cannot draw is listed as skipped, not an error), then calls
// write_report_index last, which writes DIR/index.html (report/html_page.hpp) listing every
// figure with its caption, every skipped plot with the reason, and links to the text files and
// to the data files the command wrote (relative to DIR). Every file goes through a temporary
// name and a rename (io/atomic_file.hpp).

#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"
#include "report/html_page.hpp"

namespace shudder::report {

struct Report {
  std::vector<std::string> files;               // written, in order (paths under DIR)
  std::vector<std::string> skipped;             // "spectrum.png: <why>" for plots not drawn
  std::map<std::string, std::string> captions;  // file name -> what the figure shows (Plot::caption)
};

/// Creates the report directory `dir` (and its parents); io::InputError naming it when it cannot.
void make_report_dir(const std::string& dir);

/// Writes `figure` (or `plot`) to `dir`/`file` and lists it in `report.files` (its caption in
/// `report.captions`); a plot gnuplot fails to draw is listed in `report.skipped` with gnuplot's
/// reason instead. An unwritable destination stays an io::InputError.
void add_report_plot(Report& report, const std::string& dir, const std::string& file, const MultiPlot& figure);
void add_report_plot(Report& report, const std::string& dir, const std::string& file, const Plot& plot);

/// The `report.skipped` reason for plots when gnuplot is not on PATH.
inline constexpr const char* kGnuplotMissing = "gnuplot not found; install gnuplot (Debian: gnuplot-nox)";

/// What index.html says beyond the directory's files.
struct ReportIndex {
  std::string title;          // e.g. "shudder run: rig_case1_25kN_378Hz"
  std::string verdict;        // one sentence; empty = none
  std::string verdict_class;  // "shudder", "none" or "" (see HtmlPage)
  std::string summary;        // the printed summary
  std::vector<HtmlTable> tables;
  std::vector<std::string> data_files;  // files the command wrote outside DIR (as given, relative
                                        // to the working directory or absolute); linked relative to DIR
};

/// The paths among `paths` that are not empty (a command's optional outputs, for data_files).
std::vector<std::string> report_data_files(std::initializer_list<std::string> paths);

/// Writes `dir`/index.html from `index` and `report` (its PNG files as figures, its other files
/// and `index.data_files` as links, its skipped plots) and appends it to `report.files`.
void write_report_index(const std::string& dir, const ReportIndex& index, Report& report);

/// The verdict sentence and its class for a run's verdict text ("vibration", "stick-slip",
/// "none", "not_judged") and detector numbers: e.g. "Shudder: friction-induced vibration at
/// 378 Hz, amplitude 134 N m (onset 0.21 s)".
std::pair<std::string, std::string> verdict_line(const std::string& verdict, double frequency_Hz, double amplitude_Nm,
                                                 double onset_time_s);

}  // namespace shudder::report
