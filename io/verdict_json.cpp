#include "io/verdict_json.hpp"

#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/screening_json.hpp"

namespace shudder::io {

namespace {

std::string number(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

}  // namespace

std::string verdict_json(const dynamics::ResultBlock& b) {
  std::string s = "{\n  \"format\": \"shudder-verdict/1\"";
  for (const auto& t : b.texts) s += ",\n  " + json_string(t.name) + ": " + json_string(t.value);
  for (const auto& sc : b.scalars) s += ",\n  " + json_string(sc.name) + ": " + number(sc.value);
  return s + "\n}\n";
}

void write_verdict_json(const dynamics::ResultBlock& verdict, const std::string& path) {
  write_text_file_atomically(path, verdict_json(verdict));
}

}  // namespace shudder::io
