#include "io/screening_json.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/json_number.hpp"

namespace shudder::io {

namespace {

using analysis::Index;
using analysis::kIndexCount;

const char* boolean(bool b) { return b ? "true" : "false"; }

// "[a, b, ...]" of f(i) for i < n.
std::string array(std::size_t n, const std::function<std::string(std::size_t)>& f) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) s += ", ";
    s += f(i);
  }
  return s + "]";
}

std::string numbers(const std::vector<double>& v) {
  return array(v.size(), [&](std::size_t i) { return json_number(v[i]); });
}

// Rows of a (n_s x n_T) matrix: [[m(0,0), m(0,1), ...], ...], one row per speed.
std::string matrix(const Eigen::MatrixXd& m) {
  return array(static_cast<std::size_t>(m.rows()), [&](std::size_t i) {
    return array(static_cast<std::size_t>(m.cols()), [&](std::size_t j) {
      return json_number(m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
    });
  });
}

std::string runs(const std::vector<analysis::RegionRun>& r) {
  return array(r.size(), [&](std::size_t i) {
    return "{\"temp_C\": " + json_number(r[i].temp_C) + ", \"from_rpm\": " + json_number(r[i].from_rpm) +
           ", \"to_rpm\": " + json_number(r[i].to_rpm) + "}";
  });
}

std::string extent(const analysis::RegionExtent& e) {
  std::ostringstream os;
  os << "{\"points\": " << e.points << ", \"grid_points\": " << e.grid_points;
  if (e.points > 0)
    os << ", \"speed_rpm\": [" << json_number(e.min_rpm) << ", " << json_number(e.max_rpm) << "], \"temp_C\": ["
       << json_number(e.min_temp_C) << ", " << json_number(e.max_temp_C) << "]";
  os << "}";
  return os.str();
}

}  // namespace

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += ch;  // UTF-8 bytes pass through
        }
    }
  }
  return out + "\"";
}

std::string screening_json(const studies::ScreeningReport& rep, const std::string& fluid_file) {
  const auto& idx = rep.indices;
  const std::size_t nt = idx.size();
  std::ostringstream os;
  os << "{\n";
  os << "  \"format\": \"shudder-screen/1\",\n";
  os << "  \"shudder_version\": " << json_string(SHUDDER_VERSION) << ",\n";
  os << "  \"fluid\": " << json_string(rep.fluid_name) << ",\n";
  os << "  \"fluid_file\": " << json_string(fluid_file) << ",\n";
  os << "  \"load_N\": " << json_number(rep.load_N) << ",\n";
  os << "  \"mean_radius_mm\": " << json_number(rep.mean_radius_mm) << ",\n";
  os << "  \"mm_s_per_rpm\": " << json_number(analysis::rpm_to_mm_s(1.0, rep.mean_radius_mm)) << ",\n";
  os << "  \"law_data_range\": {\"speed_mm_s\": [" << json_number(rep.law_speed_range_mm_s.first) << ", "
     << json_number(rep.law_speed_range_mm_s.second) << "], \"temp_C\": [" << json_number(rep.law_temp_range_C.first)
     << ", " << json_number(rep.law_temp_range_C.second) << "]},\n";

  // Indices: one array per index, aligned with temperatures_C.
  os << "  \"temperatures_C\": " << array(nt, [&](std::size_t i) { return json_number(idx[i].temp_C); }) << ",\n";
  os << "  \"temperature_outside_data\": "
     << array(nt, [&](std::size_t i) { return std::string(boolean(idx[i].temp_outside_data)); }) << ",\n";
  for (std::size_t k = 0; k < kIndexCount; ++k)
    os << "  \"" << analysis::index_info()[k].key
       << "\": " << array(nt, [&](std::size_t i) { return json_number(idx[i].values[k].value); }) << ",\n";
  os << "  \"units\": {";
  for (std::size_t k = 0; k < kIndexCount; ++k)
    os << (k ? ", " : "") << "\"" << analysis::index_info()[k].key
       << "\": " << json_string(analysis::index_info()[k].unit);
  os << "},\n";
  os << "  \"clamped\": {\n";
  for (std::size_t k = 0; k < kIndexCount; ++k)
    os << "    \"" << analysis::index_info()[k].key
       << "\": " << array(nt, [&](std::size_t i) { return std::string(boolean(idx[i].values[k].clamped)); })
       << (k + 1 < kIndexCount ? ",\n" : "\n");
  os << "  },\n";

  // Slope map and its negative (risky) region.
  os << "  \"slope_map\": {\"speeds_rpm\": " << numbers(rep.slope.speeds_rpm)
     << ", \"temps_C\": " << numbers(rep.slope.temps_C) << ", \"dmu_dv_s_per_m\": " << matrix(rep.slope.dmu_dv_s_per_m)
     << "},\n";
  os << "  \"risky_region\": " << runs(rep.negative_slope) << ",\n";
  os << "  \"risky_region_extent\": " << extent(rep.negative_slope_extent) << ",\n";

  // Stability maps, one per rig, on the slope map's grid.
  os << "  \"stability\": {\"load_N\": " << json_number(rep.load_N)
     << ", \"speeds_rpm\": " << numbers(rep.slope.speeds_rpm) << ", \"temps_C\": " << numbers(rep.slope.temps_C)
     << ", \"rigs\": [";
  for (std::size_t r = 0; r < rep.rigs.size(); ++r) {
    const auto& rig = rep.rigs[r];
    os << (r ? ",\n" : "\n") << "    {\"label\": " << json_string(rig.label)
       << ", \"clutch_side_frequency_Hz\": " << json_number(rig.clutch_side_frequency_Hz)
       << ", \"unstable_region\": " << runs(rig.unstable) << ", \"unstable_extent\": " << extent(rig.unstable_extent)
       << ", \"saturated_points\": " << rig.saturated_points
       << ", \"max_margin_per_s\": " << json_number(rig.max_margin_per_s)
       << ", \"max_margin_at\": {\"speed_rpm\": " << json_number(rig.max_margin_rpm)
       << ", \"temp_C\": " << json_number(rig.max_margin_temp_C)
       << ", \"frequency_Hz\": " << json_number(rig.max_margin_frequency_Hz) << "}"
       << ", \"margin_per_s\": " << matrix(rig.map.margin_per_s)
       << ", \"frequency_Hz\": " << matrix(rig.map.frequency_Hz) << "}";
  }
  os << (rep.rigs.empty() ? "]},\n" : "\n  ]},\n");

  os << "  \"verdict_level\": " << json_string(analysis::risk_level_name(rep.verdict.level)) << ",\n";
  os << "  \"verdict\": " << json_string(rep.verdict.text) << "\n";
  os << "}\n";
  return os.str();
}

void write_screening_json(const studies::ScreeningReport& report, const std::string& fluid_file,
                          const std::string& path) {
  write_text_file_atomically(path, screening_json(report, fluid_file));
}

}  // namespace shudder::io
