#include "io/comparison_json.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/screening_json.hpp"
#include "io/json_number.hpp"

namespace shudder::io {

namespace {

std::string indices(const analysis::AntiShudderIndices& at) {
  std::string s = "{";
  for (std::size_t k = 0; k < analysis::kIndexCount; ++k)
    s += std::string(k ? ", " : "") + "\"" + analysis::index_info()[k].key + "\": " + json_number(at.values[k].value);
  return s + "}";
}

}  // namespace

std::string comparison_json(const studies::Comparison& c) {
  std::ostringstream o;
  o << "{\n  \"format\": \"shudder-compare/1\",\n  \"load_N\": " << json_number(c.load_N)
    << ",\n  \"viscosity_cSt\": " << json_number(c.viscosity_cSt) << ",\n  \"temperatures_C\": [";
  for (std::size_t i = 0; i < c.temps_C.size(); ++i) o << (i ? ", " : "") << json_number(c.temps_C[i]);
  o << "],\n  \"fluids\": [";
  for (std::size_t i = 0; i < c.fluids.size(); ++i) {
    const auto& f = c.fluids[i];
    o << (i ? "," : "") << "\n    {\"name\": " << json_string(f.name) << ", \"file\": " << json_string(f.file)
      << ", \"rank\": " << f.rank << ", \"verdict\": " << json_string(f.screen.verdict.text)
      << ", \"breakaway_ratio\": " << json_number(f.breakaway_ratio)
      << ", \"largest_margin_per_s\": " << json_number(f.worst_margin_per_s)
      << ", \"largest_mu1_over_mu50\": " << json_number(f.worst_mu1_over_mu50)
      << ",\n     \"equal_viscosity\": {\"temp_C\": " << json_number(f.equal_viscosity_temp_C)
      << ", \"indices\": " << indices(f.at_equal_viscosity) << "},\n     \"at_temperatures\": [";
    for (std::size_t k = 0; k < f.screen.indices.size(); ++k)
      o << (k ? ", " : "") << "{\"temp_C\": " << json_number(f.screen.indices[k].temp_C)
        << ", \"mu50\": " << json_number(f.mu50[k]) << ", \"indices\": " << indices(f.screen.indices[k]) << "}";
    o << "]}";
  }
  o << "\n  ],\n  \"separations\": [";
  for (std::size_t i = 0; i < c.separations.size(); ++i) o << (i ? ", " : "") << json_string(c.separations[i]);
  o << "]\n}\n";
  return o.str();
}

}  // namespace shudder::io
