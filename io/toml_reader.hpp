#pragma once
// Strict reading of a TOML table: every value is checked for type, finiteness and range, every
// key read is remembered, and finish() rejects keys nobody read (a misspelt key must not be
// silently ignored). All failures throw InputError naming the file, line, full key and the
// allowed values.

#include <toml++/toml.h>

#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/nearest_name.hpp"
#include "io/input_error.hpp"

namespace shudder::io {

/// Allowed closed/open interval for a number; printed in error messages.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static Range closed(double lo, double hi) { return {lo, hi}; }
  bool contains(double x) const;
  std::string describe() const;
};

using shudder::edit_distance;  // core/nearest_name.hpp
using shudder::nearest_key;

/// "a table", "an array", "a string", ... for messages about a value of the wrong type.
const char* toml_type_name(const toml::node& n);

class TomlTable {
 public:
  TomlTable(const toml::table& table, std::string file, std::string path);

  /// Parses a whole file; a syntax error or an unreadable file throws InputError.
  static toml::table parse_file(const std::string& file);
  /// Parses text; `file` names it in messages.
  static toml::table parse_text(const std::string& text, const std::string& file);

  bool has(const std::string& key) const;
  bool is_array(const std::string& key) const;
  bool is_table(const std::string& key) const;

  double number(const std::string& key, Range range = {});
  double number_or(const std::string& key, double fallback, Range range = {});
  long integer(const std::string& key, long min, long max);
  long integer_or(const std::string& key, long fallback, long min, long max);
  bool boolean(const std::string& key);
  bool boolean_or(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  /// A string that must be one of `choices`.
  std::string choice_or(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices);
  /// Array of numbers (integers accepted), each within `range`; `min_size` elements at least.
  std::vector<double> numbers(const std::string& key, Range range = {}, std::size_t min_size = 1);

  TomlTable table(const std::string& key);
  std::optional<TomlTable> optional_table(const std::string& key);
  std::vector<TomlTable> table_array(const std::string& key);
  /// The keys of this table that hold sub-tables (e.g. the effect names under [effects]).
  std::vector<std::string> subtable_keys() const;

  /// Throws for the first key that no accessor read, naming the nearest key that was read
  /// ("did you mean") and listing all of them.
  void finish() const;

  /// An error about `key` in this table, with the key's line when known.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  const std::string& file() const { return file_; }
  std::string full_key(const std::string& key) const;
  /// Marks a key as read without reading it (for keys handled elsewhere).
  void mark_read(const std::string& key) { read_.insert(key); }

 private:
  const toml::node* get(const std::string& key) const;
  /// A required key is absent: if an unread key of this table is one edit away from it,
  /// reports THAT key as unknown ("did you mean"), else "KEY: missing; <expected>".
  [[noreturn]] void missing(const std::string& key, const std::string& expected) const;
  long line_of(const std::string& key) const;

  const toml::table* table_;
  std::string file_;
  std::string path_;  // dotted path of this table, "" at the root
  std::set<std::string> read_;
};

}  // namespace shudder::io
