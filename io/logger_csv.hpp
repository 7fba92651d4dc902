#pragma once
// A test-rig logger's CSV as it comes: any column names, delimiter ',', ';' or tab, decimal
// point '.' or ',', optional '#' lines before the header (those of the form '# key: value' are
// kept as metadata). Only numbers are read: a field that is not a number is an InputError
// naming the file, line and column. `shudder import` (io/logger_import.hpp) turns the table
// into a measured run; docs/formats/import_mapping.md describes the rules.

#include <string>
#include <utility>
#include <vector>

namespace shudder::io {

struct LoggerCsvOptions {
  char delimiter = 0;  // 0 = detect from the header line (';' or tab if present, else ',')
  char decimal = 0;    // 0 = detect: ',' when the delimiter is not ',' and a number has ','
};

struct LoggerTable {
  std::string path;
  char delimiter = ',';
  char decimal = '.';
  std::vector<std::pair<std::string, std::string>> metadata;  // '# key: value' lines
  std::vector<std::string> names;                             // header fields, trimmed
  std::vector<std::vector<double>> columns;                   // one per name, equal lengths
  std::vector<long> row_lines;                                // file line of each row
};

/// Reads `path`; InputError (file, line, column, what is allowed) on anything it cannot read.
LoggerTable read_logger_csv(const std::string& path, const LoggerCsvOptions& options = {});

/// "comma", "semicolon", "tab" for messages and the import's summary.
std::string delimiter_name(char delimiter);

}  // namespace shudder::io
