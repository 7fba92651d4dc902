// Reading a logger's CSV (see logger_csv.hpp). The whole file is read first: the delimiter is
// decided on the header line, the decimal separator on all data fields, then every field is
// parsed with std::from_chars (independent of the C locale).
#include "io/logger_csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "io/input_error.hpp"

namespace shudder::io {

namespace logger_csv_impl {

std::string_view trimmed(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::string_view unquoted(std::string_view s) {
  s = trimmed(s);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = trimmed(s.substr(1, s.size() - 2));
  return s;
}

std::vector<std::string_view> fields_of(std::string_view line, char delimiter) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const auto at = line.find(delimiter, start);
    out.push_back(unquoted(line.substr(start, at == std::string_view::npos ? at : at - start)));
    if (at == std::string_view::npos) return out;
    start = at + 1;
  }
}

char detect_delimiter(std::string_view header) {
  const auto count = [&](char c) { return std::count(header.begin(), header.end(), c); };
  if (count('\t') > 0 && count('\t') >= count(';')) return '\t';
  if (count(';') > 0) return ';';
  return ',';
}

struct Line {
  long number;
  std::string text;
};

}  // namespace logger_csv_impl

std::string delimiter_name(char delimiter) {
  switch (delimiter) {
    case ',': return "comma";
    case ';': return "semicolon";
    case '\t': return "tab";
    default: return std::string("'") + delimiter + "'";
  }
}

LoggerTable read_logger_csv(const std::string& path, const LoggerCsvOptions& options) {
  using namespace logger_csv_impl;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, "", "cannot read logger file: no such file (or not a regular file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open logger file for reading");

  LoggerTable t;
  t.path = path;
  std::vector<Line> rows;
  long header_line = 0;
  std::string header;
  std::string text;
  for (long number = 1; std::getline(in, text); ++number) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (number == 1 && text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);
    if (trimmed(text).empty()) continue;  // blank lines anywhere are skipped
    if (!header_line && text.starts_with('#')) {
      const std::string_view body = std::string_view(text).substr(1);
      if (const auto colon = body.find(':'); colon != std::string_view::npos) {
        const std::string key(trimmed(body.substr(0, colon)));
        if (!key.empty() && key.find(' ') == std::string::npos)
          t.metadata.emplace_back(key, std::string(trimmed(body.substr(colon + 1))));
      }
      continue;  // other '#' lines before the header are comments
    }
    if (!header_line) {
      header_line = number;
      header = text;
    } else {
      rows.push_back({number, text});
    }
  }
  if (in.bad()) throw InputError(path, 0, "", "read error");
  if (!header_line)
    throw InputError(path, 1, "",
                     "no header line: the file is empty or only '#' lines; a logger file is a header "
                     "naming the columns, then one row of numbers per sample");

  t.delimiter = options.delimiter ? options.delimiter : detect_delimiter(header);
  auto names = fields_of(header, t.delimiter);
  // A delimiter after the last field on every line (some loggers write one): an empty last name.
  const bool trailing = names.size() > 1 && names.back().empty();
  if (trailing) names.pop_back();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string name(names[i]);
    if (name.empty())
      throw InputError(path, header_line, "",
                       "header field " + std::to_string(i + 1) + " is empty; every column needs a name");
    if (std::find(t.names.begin(), t.names.end(), name) != t.names.end())
      throw InputError(path, header_line, "", "column '" + name + "' is named twice; column names must be unique");
    t.names.push_back(name);
  }
  if (t.names.size() < 2)
    throw InputError(path, header_line, "",
                     "the header has one column ('" + t.names.front() + "'); the delimiter was taken as " +
                         delimiter_name(t.delimiter) +
                         "; allowed delimiters: comma, semicolon, tab (or give --delimiter)");

  // Decimal comma: only possible when ',' is not the delimiter; decided by any field holding one.
  t.decimal = options.decimal ? options.decimal : '.';
  std::vector<std::vector<std::string_view>> split;
  split.reserve(rows.size());
  for (const auto& row : rows) {
    auto f = fields_of(row.text, t.delimiter);
    if (trailing && f.size() == t.names.size() + 1 && f.back().empty()) f.pop_back();
    if (f.size() != t.names.size())
      throw InputError(path, row.number, "",
                       "row has " + std::to_string(f.size()) + " field(s) but the header (line " +
                           std::to_string(header_line) + ") has " + std::to_string(t.names.size()) +
                           " columns (delimiter: " + delimiter_name(t.delimiter) +
                           "); every row needs one value per column");
    if (!options.decimal && t.delimiter != ',')
      for (const auto& field : f)
        if (field.find(',') != std::string_view::npos) t.decimal = ',';
    split.push_back(std::move(f));
  }
  if (t.decimal == ',' && t.delimiter == ',')
    throw InputError(path, header_line, "",
                     "decimal comma with comma-separated columns cannot be read; allowed: "
                     "decimal ',' with ';' or tab as the delimiter");

  t.columns.assign(t.names.size(), {});
  for (auto& c : t.columns) c.reserve(rows.size());
  std::string number;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < t.names.size(); ++c) {
      const std::string_view field = split[r][c];
      const auto fail = [&](const std::string& why) {
        throw InputError(path, rows[r].number, "", "column '" + t.names[c] + "': '" + std::string(field) + "' " + why);
      };
      if (field.empty()) fail("is empty; every field must be a number");
      number.assign(field);
      if (t.decimal == ',') {
        if (number.find('.') != std::string::npos)
          fail("mixes '.' and ',' (thousands separators are not read); allowed: digits with one decimal ','");
        std::replace(number.begin(), number.end(), ',', '.');
      }
      const char* first = number.data() + (number.front() == '+' ? 1 : 0);
      double v = 0.0;
      const auto res = std::from_chars(first, number.data() + number.size(), v);
      if (res.ec != std::errc() || res.ptr != number.data() + number.size())
        fail(std::string("is not a number; allowed: a decimal number such as 12, -0.5 or 1.2e-3 (decimal ") +
             (t.decimal == ',' ? "','" : "'.'") + ")");
      if (!std::isfinite(v)) fail("is not finite; every value must be a finite number");
      t.columns[c].push_back(v);
    }
    t.row_lines.push_back(rows[r].number);
  }
  return t;
}

}  // namespace shudder::io
