// `run --report DIR` for every kind of scenario and for networks (app/commands.hpp).
#include <iostream>
#include <stdexcept>

#include "app/commands.hpp"
#include "io/input_error.hpp"
#include "report/run_report_directory.hpp"

namespace shudder::app {

int write_report_directory(const std::string& dir, const dynamics::Recording& rec, const std::string& name,
                           const std::string& summary, bool rig_plots, const std::string& run_file) {
  try {
    const report::Report report = report::write_run_report(dir, rec, name, summary, rig_plots, run_file);
    std::cout << "Report: " << dir << " (" << report.files.size() << " files)\n";
    for (const auto& s : report.skipped) std::cerr << "shudder: warning: report: " << s << "\n";
  } catch (const io::InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::cerr << "shudder: report failed: " << e.what() << " (the run itself is in " << run_file << ")\n";
    return 1;
  }
  return 0;
}

}  // namespace shudder::app
