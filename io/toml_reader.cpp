#include "io/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace shudder::io {

bool Range::contains(double x) const {
  if (min_exclusive ? !(x > min) : !(x >= min)) return false;
  if (max_exclusive ? !(x < max) : !(x <= max)) return false;
  return true;
}

std::string Range::describe() const {
  std::ostringstream os;
  os.precision(10);
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max)
    os << (min_exclusive ? "(" : "[") << min << ", " << max << (max_exclusive ? ")" : "]");
  else if (has_min)
    os << (min_exclusive ? "> " : ">= ") << min;
  else if (has_max)
    os << (max_exclusive ? "< " : "<= ") << max;
  else
    os << "any finite number";
  return os.str();
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between a's first i and b's first j characters (Wagner–Fischer with the
  // adjacent-swap case of Damerau).
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string nearest_key(const std::string& key, const std::vector<std::string>& candidates) {
  const std::size_t limit = std::min<std::size_t>(2, key.size() / 3);
  std::string best;
  std::size_t best_d = limit + 1;
  for (const auto& c : candidates) {
    const std::size_t dist = edit_distance(key, c);
    if (dist < best_d) {
      best_d = dist;
      best = c;
    }
  }
  return best;
}

TomlTable::TomlTable(const toml::table& table, std::string file, std::string path)
    : table_(&table), file_(std::move(file)), path_(std::move(path)) {}

toml::table TomlTable::parse_file(const std::string& file) {
  try {
    return toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    // toml++ reports an unreadable file as a parse error at line 0.
    throw InputError(file, static_cast<long>(src.begin.line), "",
                     std::string(e.description()));
  }
}

toml::table TomlTable::parse_text(const std::string& text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw InputError(file, static_cast<long>(e.source().begin.line), "", std::string(e.description()));
  }
}

std::string TomlTable::full_key(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

long TomlTable::line_of(const std::string& key) const {
  if (const auto* n = table_->get(key)) return static_cast<long>(n->source().begin.line);
  return static_cast<long>(table_->source().begin.line);
}

void TomlTable::fail(const std::string& key, const std::string& message) const {
  throw InputError(file_, line_of(key), full_key(key), message);
}

bool TomlTable::has(const std::string& key) const { return table_->contains(key); }

bool TomlTable::is_array(const std::string& key) const {
  const auto* n = get(key);
  return n && n->is_array();
}

const toml::node* TomlTable::get(const std::string& key) const { return table_->get(key); }

void TomlTable::missing(const std::string& key, const std::string& expected) const {
  // Keys are read in the loader's order, so a misspelt required key is met as the correct one
  // missing; the misspelling itself is the better report. Only unread keys one edit away count:
  // an unread key may still be a correct key read later, and correct keys lie two edits apart
  // (nu40_cSt / nu100_cSt) but, among the required ones, never one.
  for (const auto& [k, v] : *table_) {
    const std::string u(k.str());
    if (!read_.count(u) && edit_distance(u, key) == 1)
      throw InputError(file_, line_of(u), full_key(u), "unknown key; did you mean '" + key + "'?");
  }
  fail(key, "missing; " + expected);
}

const char* toml_type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

double TomlTable::number(const std::string& key, Range range) {
  const auto* n = get(key);
  if (!n) missing(key, "expected a number in " + range.describe());
  read_.insert(key);
  double x = 0.0;
  if (auto v = n->as_floating_point())
    x = v->get();
  else if (auto i = n->as_integer())
    x = static_cast<double>(i->get());
  else
    fail(key, std::string("is ") + toml_type_name(*n) + "; expected a number in " + range.describe());
  if (!std::isfinite(x)) fail(key, "is not finite (nan/inf); expected a number in " + range.describe());
  if (!range.contains(x)) {
    std::ostringstream os;
    os.precision(10);
    os << "value " << x << " is out of range; allowed " << range.describe();
    fail(key, os.str());
  }
  return x;
}

double TomlTable::number_or(const std::string& key, double fallback, Range range) {
  return has(key) ? number(key, range) : (read_.insert(key), fallback);
}

long TomlTable::integer(const std::string& key, long min, long max) {
  const auto* n = get(key);
  const std::string allowed =
      "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (!n) missing(key, allowed);
  read_.insert(key);
  const auto* i = n->as_integer();
  if (!i) fail(key, std::string("is ") + toml_type_name(*n) + "; " + allowed);
  const long x = static_cast<long>(i->get());
  if (x < min || x > max) fail(key, "value " + std::to_string(x) + " is out of range; " + allowed);
  return x;
}

long TomlTable::integer_or(const std::string& key, long fallback, long min, long max) {
  return has(key) ? integer(key, min, max) : (read_.insert(key), fallback);
}

bool TomlTable::boolean(const std::string& key) {
  const auto* n = get(key);
  if (!n) missing(key, "expected true or false");
  read_.insert(key);
  const auto* b = n->as_boolean();
  if (!b) fail(key, std::string("is ") + toml_type_name(*n) + "; expected true or false");
  return b->get();
}

bool TomlTable::boolean_or(const std::string& key, bool fallback) {
  return has(key) ? boolean(key) : (read_.insert(key), fallback);
}

std::string TomlTable::string(const std::string& key) {
  const auto* n = get(key);
  if (!n) missing(key, "expected a string");
  read_.insert(key);
  const auto* s = n->as_string();
  if (!s) fail(key, std::string("is ") + toml_type_name(*n) + "; expected a string");
  return s->get();
}

std::string TomlTable::string_or(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : (read_.insert(key), fallback);
}

std::string TomlTable::choice_or(const std::string& key, const std::string& fallback,
                                 const std::vector<std::string>& choices) {
  const std::string v = string_or(key, fallback);
  for (const auto& c : choices)
    if (c == v) return v;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
  fail(key, "\"" + v + "\" is not allowed; expected one of " + list);
}

std::vector<double> TomlTable::numbers(const std::string& key, Range range,
                                       std::size_t min_size) {
  const auto* n = get(key);
  const std::string allowed = "expected an array of at least " + std::to_string(min_size) +
                              " numbers in " + range.describe();
  if (!n) missing(key, allowed);
  read_.insert(key);
  const auto* arr = n->as_array();
  if (!arr) fail(key, std::string("is ") + toml_type_name(*n) + "; " + allowed);
  std::vector<double> out;
  out.reserve(arr->size());
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto& e = *arr->get(i);
    double x = 0.0;
    if (auto v = e.as_floating_point())
      x = v->get();
    else if (auto iv = e.as_integer())
      x = static_cast<double>(iv->get());
    else
      fail(key, "element " + std::to_string(i) + " is " + toml_type_name(e) + "; " + allowed);
    if (!std::isfinite(x)) fail(key, "element " + std::to_string(i) + " is not finite; " + allowed);
    if (!range.contains(x)) {
      std::ostringstream os;
      os.precision(10);
      os << "element " << i << " = " << x << " is out of range; allowed " << range.describe();
      fail(key, os.str());
    }
    out.push_back(x);
  }
  if (out.size() < min_size) fail(key, "has " + std::to_string(out.size()) + " elements; " + allowed);
  return out;
}

TomlTable TomlTable::table(const std::string& key) {
  const auto* n = get(key);
  if (!n) fail(key, "missing table [" + full_key(key) + "]");
  read_.insert(key);
  const auto* t = n->as_table();
  if (!t) fail(key, std::string("is ") + toml_type_name(*n) + "; expected a table");
  return TomlTable(*t, file_, full_key(key));
}

std::optional<TomlTable> TomlTable::optional_table(const std::string& key) {
  if (!has(key)) {
    read_.insert(key);
    return std::nullopt;
  }
  return table(key);
}

std::vector<TomlTable> TomlTable::table_array(const std::string& key) {
  const auto* n = get(key);
  if (!n) missing(key, "expected an array of tables [[" + full_key(key) + "]]");
  read_.insert(key);
  const auto* arr = n->as_array();
  if (!arr) fail(key, std::string("is ") + toml_type_name(*n) + "; expected an array of tables");
  std::vector<TomlTable> out;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto* t = arr->get(i)->as_table();
    if (!t) fail(key, "element " + std::to_string(i) + " is not a table");
    out.emplace_back(*t, file_, full_key(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

std::vector<std::string> TomlTable::subtable_keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : *table_)
    if (v.is_table()) out.emplace_back(k.str());
  return out;
}

void TomlTable::finish() const {
  for (const auto& [k, v] : *table_) {
    const std::string key(k.str());
    if (read_.count(key)) continue;
    std::string allowed;
    for (const auto& r : read_) allowed += (allowed.empty() ? "" : ", ") + r;
    const std::string near = nearest_key(key, {read_.begin(), read_.end()});
    throw InputError(file_, static_cast<long>(v.source().begin.line), full_key(key),
                     "unknown key; " + (near.empty() ? "" : "did you mean '" + near + "'? ") +
                         "allowed keys here: " + (allowed.empty() ? "(none)" : allowed));
  }
}

}  // namespace shudder::io
