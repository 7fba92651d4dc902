// `shudder import`: a test-rig logger's CSV -> a measured run (docs/formats/import_mapping.md).
// Parsing and printing only: the mapping, conversion and checks are io/logger_import.
#include <cstdio>
#include <iostream>
#include <string>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/logger_csv.hpp"
#include "io/logger_import.hpp"
#include "io/measured_run.hpp"
#include "io/measurement_csv.hpp"
#include "io/output_safety.hpp"

namespace shudder::app {

namespace {

bool is_hdf5_name(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos) return false;
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".h5" || ext == ".hdf5";
}

}  // namespace

io::ImportSpec import_spec(const ImportOptions& o) {
  io::ImportSpec spec;
  for (const auto& m : o.maps) spec.maps.push_back(io::parse_map_option(m));
  for (const auto& m : o.metas) spec.metadata.push_back(io::parse_meta_option(m));
  spec.delimiter = io::parse_delimiter(o.delimiter, "--delimiter");
  spec.decimal = io::parse_decimal(o.decimal, "--decimal");
  spec.trust_units = o.trust_units;
  if (!o.mapping.empty()) io::read_import_mapping(o.mapping, spec);
  return spec;
}

int import_command(const ImportOptions& o) {
  return guarded(o.logger, "import", [&] {
    std::vector<io::RolePath> inputs = {{"logger file", o.logger}};
    if (!o.mapping.empty()) inputs.push_back({"--mapping", o.mapping});
    io::require_distinct_paths(inputs, {{"-o", o.output}});
    io::require_output_directory(o.output);
    const io::ImportSpec spec = import_spec(o);
    io::ImportResult r = io::import_logger(o.logger, spec);
    for (const auto& w : r.warnings) std::cerr << "shudder: warning: " << w << "\n";
    r.run.path = o.output;
    if (is_hdf5_name(o.output))
      io::write_measured_run_hdf5(o.output, r.run);
    else
      io::write_measured_run_csv(o.output, r.run);
    const auto& t = r.run.required("time_s");
    std::printf("Imported %s (%s-separated, decimal %s): %zu rows, %.6g-%.6g s\n", o.logger.c_str(),
                io::delimiter_name(r.delimiter).c_str(), r.decimal == ',' ? "comma" : "point", r.run.rows(), t.front(),
                t.back());
    for (const auto& m : r.mapping) std::printf("  %s\n", m.c_str());
    if (!r.ignored.empty()) {
      std::string names;
      for (const auto& n : r.ignored) names += (names.empty() ? "" : ", ") + n;
      std::printf("  not written: %s\n", names.c_str());
    }
    std::printf("Wrote %s (%s)\n", o.output.c_str(), std::string(io::measured_run_format).c_str());
    return 0;
  });
}

}  // namespace shudder::app
