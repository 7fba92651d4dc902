#include "io/verdict_json.hpp"

#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/screening_json.hpp"
#include "io/json_number.hpp"

namespace shudder::io {

namespace {}  // namespace

std::string verdict_json(const dynamics::ResultBlock& b) {
  std::string s = "{\n  \"format\": \"shudder-verdict/1\"";
  for (const auto& t : b.texts) s += ",\n  " + json_string(t.name) + ": " + json_string(t.value);
  for (const auto& sc : b.scalars) s += ",\n  " + json_string(sc.name) + ": " + json_number(sc.value);
  return s + "\n}\n";
}

void write_verdict_json(const dynamics::ResultBlock& verdict, const std::string& path) {
  write_text_file_atomically(path, verdict_json(verdict));
}

}  // namespace shudder::io
