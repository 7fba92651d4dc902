#include "io/sweep_spec.hpp"

#include <charconv>
#include <cmath>
#include <new>

#include "io/input_error.hpp"

namespace shudder::io {

namespace {

constexpr std::size_t kMaxValuesPerAxis = 100000;

constexpr const char* kSweepForm = "KEY=START:STOP:STEP (STEP > 0, STOP >= START) or KEY=V1,V2,...";
constexpr const char* kRunForm = "KEY=VALUE (one number; `shudder sweep` runs several values)";

[[noreturn]] void bad(const std::string& arg, const std::string& why, const char* form = kSweepForm) {
  throw InputError("--set", 0, "", "'" + arg + "': " + why + "; expected " + form);
}

double number(const std::string& arg, const std::string& text, const char* form = kSweepForm) {
  double x = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, x);
  if (ec != std::errc() || ptr != end || !std::isfinite(x)) bad(arg, "'" + text + "' is not a finite number", form);
  return x;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t pos; (pos = s.find(sep, start)) != std::string::npos; start = pos + 1)
    out.push_back(s.substr(start, pos - start));
  out.push_back(s.substr(start));
  return out;
}

}  // namespace

SweepAxis parse_sweep_axis(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0) bad(arg, "no KEY=");
  SweepAxis axis{arg.substr(0, eq), {}};
  const std::string spec = arg.substr(eq + 1);
  if (spec.find(':') != std::string::npos) {
    const auto parts = split(spec, ':');
    if (parts.size() != 3) bad(arg, "a range needs START:STOP:STEP");
    const double start = number(arg, parts[0]), stop = number(arg, parts[1]), step = number(arg, parts[2]);
    if (!(step > 0.0) || stop < start) bad(arg, "STEP must be > 0 and STOP >= START");
    const double n = std::floor((stop - start) / step + 1e-9);
    if (n + 1 > static_cast<double>(kMaxValuesPerAxis)) bad(arg, "more than 100000 values");
    for (long i = 0; i <= static_cast<long>(n); ++i) axis.values.push_back(start + static_cast<double>(i) * step);
  } else {
    for (const auto& v : split(spec, ',')) axis.values.push_back(number(arg, v));
  }
  return axis;
}

void require_distinct_keys(const std::vector<SweepAxis>& axes) {
  for (std::size_t a = 0; a < axes.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (axes[a].key == axes[b].key)
        throw InputError("--set", 0, axes[a].key,
                         "given twice; give each key once (list several values as KEY=V1,V2,...)");
}

SweepAxis parse_set_value(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0) bad(arg, "no KEY=", kRunForm);
  const std::string value = arg.substr(eq + 1);
  if (value.find_first_of(":,") != std::string::npos) bad(arg, "a run takes one value per key", kRunForm);
  return {arg.substr(0, eq), {number(arg, value, kRunForm)}};
}

std::vector<std::vector<double>> sweep_cases(const std::vector<SweepAxis>& axes) {
  // The whole grid is reserved first: a grid too large to hold fails here at once
  // (std::bad_alloc) instead of after filling memory row by row.
  double n_cases = 1.0;
  for (const auto& axis : axes) n_cases *= static_cast<double>(axis.values.size());
  std::vector<std::vector<double>> rows;
  if (n_cases > static_cast<double>(rows.max_size())) throw std::bad_alloc();
  const auto n = static_cast<std::size_t>(n_cases);
  rows.reserve(n);
  // Case i's value on each axis: i written in the mixed radix of the axis sizes, last digit
  // (the last axis) varying fastest.
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<double> row(axes.size());
    std::size_t rest = i;
    for (std::size_t a = axes.size(); a-- > 0;) {
      row[a] = axes[a].values[rest % axes[a].values.size()];
      rest /= axes[a].values.size();
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace shudder::io
