// Measured rig run: strict CSV and HDF5 readers and the HDF5 writer (see measured_run.hpp).
// Both readers end in the same checks (format, required columns, per-row values), so the two
// forms accept exactly the same content; only the way a place is named differs (CSV line
// number vs HDF5 dataset/attribute and row index). Numbers are parsed with std::from_chars, so
// reading does not depend on the C locale.
#include "io/measured_run.hpp"

#include <hdf5.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <stdexcept>
#include <utility>

#include "io/hdf5_util.hpp"
#include "io/input_error.hpp"
#include "io/isolated_read.hpp"

namespace shudder::io {

using namespace hdf5;

// ---- MeasuredRun ----------------------------------------------------------------------------

const std::vector<double>* MeasuredRun::column(std::string_view name) const {
  for (const auto& c : columns)
    if (c.name == name) return &c.values;
  return nullptr;
}

const std::vector<double>& MeasuredRun::required(std::string_view name) const {
  if (const auto* c = column(name)) return *c;
  throw std::logic_error("measured run '" + path + "' has no column '" + std::string(name) + "'");
}

std::optional<std::string> MeasuredRun::meta(std::string_view key) const {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return std::nullopt;
}

std::size_t MeasuredRun::rows() const { return columns.empty() ? 0 : columns.front().values.size(); }

double MeasuredRun::duration_s() const {
  const auto& t = required("time_s");
  return t.empty() ? 0.0 : t.back() - t.front();
}

std::string measured_run_units(std::string_view name) {
  static constexpr std::pair<std::string_view, std::string_view> suffixes[] = {
      {"_rpm", "rpm"}, {"_Nm", "N m"}, {"_N", "N"}, {"_C", "degC"}, {"_s", "s"}};
  for (const auto& [suffix, units] : suffixes)
    if (name.size() > suffix.size() && name.ends_with(suffix)) return std::string(units);
  return "";
}

namespace {

// ---- shared checks --------------------------------------------------------------------------

std::string number(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "(none)" : out;
}

std::string required_list() {
  std::vector<std::string> names(std::begin(measured_run_required), std::end(measured_run_required));
  return quoted_list(names);
}

const std::string& format_rule() {
  static const std::string rule = "the only format read is '" + std::string(measured_run_format) + "'";
  return rule;
}

// "" if all required columns are present, else what is missing and what was found.
std::string missing_required(const MeasuredRun& run) {
  std::vector<std::string> missing, found;
  for (const auto& c : run.columns) found.push_back(c.name);
  for (std::string_view r : measured_run_required)
    if (!run.column(r)) missing.emplace_back(r);
  if (missing.empty()) return "";
  return "missing required column(s) " + quoted_list(missing) + "; found " + quoted_list(found) +
         "; a measured run needs " + required_list() + " (other columns are kept)";
}

// Where the row checks look; indices into run.columns.
struct Layout {
  std::size_t time = 0, force = 0;
  Layout() = default;
  explicit Layout(const MeasuredRun& run) {
    for (std::size_t c = 0; c < run.columns.size(); ++c) {
      if (run.columns[c].name == "time_s") time = c;
      if (run.columns[c].name == "normal_force_N") force = c;
    }
  }
};

// Checks row `r` (all its values already stored). `where(row)` names a row for messages ("line
// 12", "row index 11"); `fail(column, row, message)` throws.
template <class Where, class Fail>
void check_row(const MeasuredRun& run, const Layout& at, std::size_t r, Where where, Fail fail) {
  for (std::size_t c = 0; c < run.columns.size(); ++c) {
    const double v = run.columns[c].values[r];
    if (!std::isfinite(v))
      fail(c, r,
           std::string(std::isnan(v) ? "value is NaN" : "value is infinite") + "; every value must be a finite number");
  }
  const auto& t = run.columns[at.time].values;
  if (r > 0 && !(t[r] > t[r - 1]))
    fail(at.time, r,
         "time_s " + number(t[r]) + " s is not after " + number(t[r - 1]) + " s at " + where(r - 1) +
             "; time_s must be strictly increasing");
  const double f = run.columns[at.force].values[r];
  if (f < 0.0) fail(at.force, r, "negative normal force " + number(f) + " N; normal_force_N must be >= 0");
}

std::string too_few_rows(std::size_t n) {
  return "only " + std::to_string(n) + " data row(s); a measured run needs at least " +
         std::to_string(measured_run_min_rows);
}

// ---- CSV ------------------------------------------------------------------------------------

void require_regular_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, "", "cannot read measured run: no such file (or not a regular file)");
}

bool is_blank(std::string_view s) { return s.find_first_not_of(" \t") == std::string_view::npos; }

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const auto comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

// Where a logger's own file goes instead (app/cmd_import.cpp).
constexpr const char* import_hint =
    " (a logger's CSV, with its own names, units, delimiter or decimal comma, is brought in with "
    "`shudder import LOG.csv -o RUN.csv`, docs/formats/import_mapping.md)";

constexpr const char* number_rule =
    "allowed: a decimal number such as 12, -0.5 or 1.2e-3 (decimal point '.', no spaces, no "
    "'+')";

class CsvReader {
 public:
  explicit CsvReader(const std::string& path) : path_(path) { run_.path = path; }

  MeasuredRun read() {
    require_regular_file(path_);
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw InputError(path_, 0, "", "cannot open measured run for reading");
    std::string text;
    while (std::getline(in, text)) {
      ++line_;
      std::string_view s = text;
      if (!s.empty() && s.back() == '\r') s.remove_suffix(1);               // Windows line ending
      if (line_ == 1 && s.starts_with("\xEF\xBB\xBF")) s.remove_prefix(3);  // UTF-8 BOM
      if (!header_line_) {
        // A blank line is an error only once something follows it: a file of blank lines is
        // reported as empty.
        if (is_blank(s)) {
          if (!first_blank_) first_blank_ = line_;
          continue;
        }
        if (first_blank_) {
          line_ = first_blank_;
          fail("",
               "blank line before the header; before it only '# key: value' metadata "
               "lines are allowed");
        }
        if (s.starts_with('#'))
          metadata(s);
        else
          header(s);
      } else {
        row(s);
      }
    }
    if (in.bad()) throw InputError(path_, line_, "", "read error");
    if (line_ == 0 || (!header_line_ && run_.metadata.empty()))
      throw InputError(
          path_, 1, "",
          "file is empty (or only blank lines); a measured run is '# format: " + std::string(measured_run_format) +
              "' metadata, a header line naming the columns, then data rows");
    if (!header_line_)
      fail("",
           "no header line: the file ends after the metadata; expected a header naming the "
           "columns, at least " +
               required_list());
    if (run_.rows() < measured_run_min_rows) {
      line_ = row_lines_.empty() ? header_line_ : row_lines_.back();
      fail("", too_few_rows(run_.rows()));
    }
    return std::move(run_);
  }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw InputError(path_, line_, key, message);
  }

  void metadata(std::string_view s) {
    const std::string_view body = s.substr(1);
    const auto colon = body.find(':');
    if (colon == std::string_view::npos)
      fail("",
           "malformed metadata line (no ':'); before the header every '#' line is "
           "'# key: value'");
    const std::string key(trim(body.substr(0, colon)));
    const std::string value(trim(body.substr(colon + 1)));
    if (key.empty()) fail("", "metadata line with an empty key; expected '# key: value'");
    for (std::size_t i = 0; i < run_.metadata.size(); ++i)
      if (run_.metadata[i].first == key)
        fail(key,
             "duplicate metadata key (first on line " + std::to_string(meta_lines_[i]) + "); each key may appear once");
    if (key == "format" && value != measured_run_format) fail(key, "format is '" + value + "'; " + format_rule());
    run_.metadata.emplace_back(key, value);
    meta_lines_.push_back(line_);
  }

  void header(std::string_view s) {
    header_line_ = line_;
    if (!run_.meta("format"))
      fail("format", "no '# format: " + std::string(measured_run_format) + "' metadata line before the header; " +
                         format_rule() + import_hint);
    const auto names = split_fields(s);
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string name(names[i]);
      if (name.empty()) fail("", "header field " + std::to_string(i + 1) + " is empty; every column needs a name");
      if (trim(name) != names[i])
        fail(name,
             "column name has leading or trailing spaces; write the header without "
             "spaces around the commas");
      for (std::size_t j = 0; j < i; ++j)
        if (names[j] == names[i])
          fail(name, "duplicate column name (header fields " + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                         "); column names must be unique");
      run_.columns.push_back({name, measured_run_units(name), {}});
    }
    if (const std::string missing = missing_required(run_); !missing.empty()) {
      const bool other_delimiter = s.find(';') != std::string_view::npos || s.find('\t') != std::string_view::npos;
      fail("", missing + (other_delimiter ? "; the header is separated by ';' or tabs, a measured run by commas" : "") +
                   import_hint);
    }
    layout_ = Layout(run_);
  }

  void row(std::string_view s) {
    if (is_blank(s)) {
      if (!first_blank_) first_blank_ = line_;
      return;
    }
    if (first_blank_) {
      const long next = line_;
      line_ = first_blank_;
      fail("", "blank line inside the data (the next row is on line " + std::to_string(next) +
                   "); blank lines are allowed only at the end of the file");
    }
    if (s.starts_with('#'))
      fail("",
           "'#' line after the header; metadata lines must all come before the header "
           "and there are no comment lines");
    const auto fields = split_fields(s);
    if (fields.size() != run_.columns.size())
      fail("", "row has " + std::to_string(fields.size()) + " field(s) but the header (line " +
                   std::to_string(header_line_) + ") has " + std::to_string(run_.columns.size()) +
                   " columns; every row needs one value per column");
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string_view f = fields[c];
      const std::string& name = run_.columns[c].name;
      if (f.empty()) fail(name, "empty field; every field must be a number");
      double v = 0.0;
      const auto res = std::from_chars(f.data(), f.data() + f.size(), v);
      if (res.ec == std::errc::result_out_of_range)
        fail(name, "'" + std::string(f) +
                       "' is out of the range of a double; values must be "
                       "finite numbers");
      if (res.ec != std::errc() || res.ptr != f.data() + f.size())
        fail(name, "'" + std::string(f) + "' is not a number; " + number_rule);
      run_.columns[c].values.push_back(v);
    }
    row_lines_.push_back(line_);
    check_row(
        run_, layout_, run_.rows() - 1, [&](std::size_t r) { return "line " + std::to_string(row_lines_[r]); },
        [&](std::size_t c, std::size_t, const std::string& message) { fail(run_.columns[c].name, message); });
  }

  const std::string& path_;
  MeasuredRun run_;
  long line_ = 0;
  long header_line_ = 0;          // 0 until the header is read
  long first_blank_ = 0;          // first blank line not yet followed by text; 0 = none
  std::vector<long> meta_lines_;  // line of each metadata entry
  std::vector<long> row_lines_;   // line of each data row
  Layout layout_;
};

// ---- HDF5 checks ----------------------------------------------------------------------------

// This file's own failures share the helpers' type: one catch converts both to InputError.
using Failure = hdf5::Error;

constexpr const char* group_name = "measurement";
const std::string group_path = "/measurement";

std::string dataset_key(const std::string& column) { return group_path + "/" + column; }
std::string attribute_key(const std::string& key) { return group_path + "@" + key; }

// Checks shared by the HDF5 reader and writer, on a run already in memory; `prefix` starts
// every message (the writer's "not written: ").
void check_hdf5_content(const std::string& path, const MeasuredRun& run, const std::string& prefix) {
  const auto bad = [&](const std::string& key, const std::string& message) {
    throw InputError(path, 0, key, prefix + message);
  };
  const auto format = run.meta("format");
  if (!format)
    bad(attribute_key("format"),
        "no 'format' attribute on /measurement; it must be the string '" + std::string(measured_run_format) + "'");
  if (*format != measured_run_format) bad(attribute_key("format"), "format is '" + *format + "'; " + format_rule());
  if (run.columns.empty()) bad(group_path, "no datasets under /measurement; a measured run needs " + required_list());
  const auto& first = run.columns.front();
  for (const auto& c : run.columns)
    if (c.values.size() != first.values.size())
      bad(dataset_key(c.name), "has " + std::to_string(c.values.size()) + " values but '" + first.name + "' has " +
                                   std::to_string(first.values.size()) + "; all columns must have the same length");
  if (const std::string missing = missing_required(run); !missing.empty()) bad(group_path, missing);
  const Layout layout(run);
  for (std::size_t r = 0; r < run.rows(); ++r)
    check_row(
        run, layout, r, [](std::size_t row) { return "row index " + std::to_string(row); },
        [&](std::size_t c, std::size_t row, const std::string& message) {
          bad(dataset_key(run.columns[c].name), "row index " + std::to_string(row) + ": " + message);
        });
  if (run.rows() < measured_run_min_rows) bad(dataset_key("time_s"), too_few_rows(run.rows()));
}

// ---- HDF5 reading ---------------------------------------------------------------------------

std::vector<std::string> attribute_names(hid_t group) {
  H5_index_t index = H5_INDEX_NAME;
  {
    const Handle gcpl = own(H5Gget_create_plist(group), H5Pclose, "read group properties");
    unsigned flags = 0;
    ok(H5Pget_attr_creation_order(gcpl, &flags), "read attribute creation order");
    if (flags & H5P_CRT_ORDER_INDEXED) index = H5_INDEX_CRT_ORDER;
  }
  std::vector<std::string> names;
  hsize_t next = 0;
  ok(H5Aiterate2(
         group, index, H5_ITER_INC, &next,
         [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
           static_cast<std::vector<std::string>*>(out)->emplace_back(name);
           return 0;
         },
         &names),
     "list attributes of /measurement");
  return names;
}

// A scalar string attribute; nullopt when it is something else (a number, an array).
std::optional<std::string> read_text_attr(hid_t obj, const std::string& name) {
  const Handle attr = own(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute '" + name + "'");
  const Handle file_type = own(H5Aget_type(attr), H5Tclose, "read type of '" + name + "'");
  if (H5Tget_class(file_type) != H5T_STRING) return std::nullopt;
  {
    const Handle space = own(H5Aget_space(attr), H5Sclose, "read shape of '" + name + "'");
    if (H5Sget_simple_extent_npoints(space) != 1) return std::nullopt;
  }
  return read_string_value(attr, file_type, name);
}

MeasuredRun read_hdf5(const std::string& path, hid_t file, std::uintmax_t max_file_bytes) {
  MeasuredRun run;
  run.path = path;
  const auto bad = [&](const std::string& key, const std::string& message) { throw InputError(path, 0, key, message); };
  const htri_t exists = H5Lexists(file, group_name, H5P_DEFAULT);
  ok(exists, "look up /measurement");
  bool is_group = false;
  if (exists > 0) {
    const Handle obj = own(H5Oopen(file, group_name, H5P_DEFAULT), H5Oclose, "open /measurement");
    is_group = H5Iget_type(obj) == H5I_GROUP;
  }
  if (!is_group)
    bad(group_path,
        "no /measurement group; the HDF5 form of a measured run keeps each column "
        "as a 1-D dataset under /measurement and the metadata as its attributes");
  const Handle group = own(H5Gopen2(file, group_name, H5P_DEFAULT), H5Gclose, "open /measurement");

  for (const auto& key : attribute_names(group)) {
    auto value = read_text_attr(group, key);
    if (!value)
      bad(attribute_key(key),
          "metadata attribute is not a string; every attribute of "
          "/measurement must be a scalar string");
    run.metadata.emplace_back(key, std::move(*value));
  }
  // The format first: a file that is not a measured run should say so, not fail on its data.
  if (const auto format = run.meta("format"); !format || *format != measured_run_format)
    check_hdf5_content(path, run, "");

  for (const auto& name : link_names(group)) {
    const std::string key = dataset_key(name);
    const Handle obj = own(H5Oopen(group, name.c_str(), H5P_DEFAULT), H5Oclose, "open " + key);
    if (H5Iget_type(obj) != H5I_DATASET)
      bad(key, "not a dataset; /measurement must hold only 1-D numeric datasets (the columns)");
    const Handle dset = own(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "open " + key);
    {
      const Handle type = own(H5Dget_type(dset), H5Tclose, "read type of " + key);
      const H5T_class_t cls = H5Tget_class(type);
      if (cls != H5T_FLOAT && cls != H5T_INTEGER)
        bad(key, "dataset is not numeric; columns must be 1-D float64 (integers are accepted)");
      // A damaged datatype can claim numbers of any size, and libhdf5 sizes its conversion
      // buffer by it before reading (found by fuzz/fuzz_measured_hdf5: a 4 GiB allocation for a
      // 10 kB file). No number libhdf5 can convert to a double is wider than 16 bytes.
      if (const std::size_t bytes = H5Tget_size(type); bytes == 0 || bytes > 16)
        bad(key, "dataset's type claims " + std::to_string(bytes) +
                     "-byte numbers; the file is "
                     "damaged (columns are float64; integers and floats of 1 to 16 bytes are accepted)");
    }
    const Handle space = own(H5Dget_space(dset), H5Sclose, "read shape of " + key);
    const int rank = H5Sget_simple_extent_ndims(space);
    if (rank < 0) throw Failure("cannot read shape of " + key + hdf5_reason());
    if (rank != 1) bad(key, "dataset has rank " + std::to_string(rank) + "; columns must be 1-D");
    hsize_t n = 0;
    ok(H5Sget_simple_extent_dims(space, &n, nullptr), "read shape of " + key);
    // A damaged dataspace can claim any length; refuse one no file of this size can hold before
    // allocating it (found by fuzz/fuzz_measured_hdf5: a 2^53-row claim ended in bad_alloc). The
    // bound allows deflate's best ratio (~1032:1) on every byte of the file.
    if (const double max_rows = 1100.0 * static_cast<double>(max_file_bytes) / sizeof(double);
        static_cast<double>(n) > max_rows)
      bad(key, "dataset claims " + std::to_string(n) + " rows, more than a " + std::to_string(max_file_bytes) +
                   "-byte file can hold even compressed; the file is damaged");
    dynamics::Signal column{name, measured_run_units(name), std::vector<double>(n)};
    if (n > 0) ok(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, column.values.data()), "read " + key);
    const htri_t has_units = H5Aexists(dset, "units");
    ok(has_units, "look up attribute 'units' of " + key);
    if (has_units > 0) {
      auto units = read_text_attr(dset, "units");
      if (!units) bad(key + "@units", "attribute 'units' is not a string");
      column.units = std::move(*units);
    }
    run.columns.push_back(std::move(column));
  }
  check_hdf5_content(path, run, "");
  return run;
}

// ---- HDF5 writing ---------------------------------------------------------------------------

void write_file(const std::string& file_name, const MeasuredRun& run,
                const std::vector<std::pair<std::string, double>>& number_attributes) {
  Handle file = own(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                    "create file '" + file_name + "'");
  {
    // Creation order tracked for links and attributes: readers get columns and metadata back in
    // file order, not sorted by name.
    const Handle gcpl = own(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "create property list");
    ok(H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "track link creation order");
    ok(H5Pset_attr_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
       "track attribute creation order");
    const Handle group =
        own(H5Gcreate2(file, group_name, H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose, "create group /measurement");
    for (const auto& [key, value] : run.metadata) write_string_attr(group, key, value);
    for (const auto& [key, value] : number_attributes) {
      const Handle space = own(H5Screate(H5S_SCALAR), H5Sclose, "create dataspace");
      const Handle attr = own(H5Acreate2(group, key.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                              "create attribute '" + key + "'");
      ok(H5Awrite(attr, H5T_NATIVE_DOUBLE, &value), "write attribute '" + key + "'");
    }
    for (const auto& c : run.columns) {
      const hsize_t n = c.values.size();
      const Handle space = own(H5Screate_simple(1, &n, nullptr), H5Sclose, "create dataspace for '" + c.name + "'");
      const Handle dset =
          own(H5Dcreate2(group, c.name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
              "create dataset '" + c.name + "'");
      if (n > 0)
        ok(H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.values.data()),
           "write dataset '" + c.name + "'");
      write_string_attr(dset, "units", c.units);
    }
  }
  ok(file.close(), "close (flush) file '" + file_name + "'");
}

// Everything that can be checked before touching the disk.
void validate_for_writing(const std::string& path, const MeasuredRun& run) {
  const std::string prefix = "not written: ";
  std::set<std::string> seen;
  for (const auto& [key, value] : run.metadata) {
    if (key.empty())
      throw InputError(path, 0, group_path,
                       prefix +
                           "a metadata key is empty; keys name "
                           "attributes and must be non-empty");
    if (!seen.insert(key).second)
      throw InputError(path, 0, attribute_key(key), prefix + "duplicate metadata key; each key may appear once");
  }
  seen.clear();
  for (const auto& c : run.columns) {
    if (c.name.empty() || c.name == "." || c.name.find('/') != std::string::npos)
      throw InputError(path, 0, dataset_key(c.name),
                       prefix + "column name must be non-empty, not '.' and contain no '/'");
    if (!seen.insert(c.name).second)
      throw InputError(path, 0, dataset_key(c.name), prefix + "duplicate column name; column names must be unique");
  }
  check_hdf5_content(path, run, prefix);
}

}  // namespace

// ---- public ---------------------------------------------------------------------------------

MeasuredRun read_measured_run(const std::string& path) {
  require_regular_file(path);
  static constexpr std::string_view signature("\x89HDF\r\n\x1a\n", 8);
  char head[signature.size()] = {};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open measured run for reading");
  in.read(head, sizeof head);
  if (static_cast<std::size_t>(in.gcount()) == signature.size() && std::string_view(head, sizeof head) == signature)
    return read_measured_run_hdf5_isolated(path);  // libhdf5 can crash or hang on damaged files
  return read_measured_run_csv(path);
}

MeasuredRun read_measured_run_csv(const std::string& path) { return CsvReader(path).read(); }

MeasuredRun read_measured_run_hdf5(const std::string& path) {
  require_regular_file(path);
  const std::lock_guard lock(hdf5_mutex());
  const QuietHdf5 quiet;
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw InputError(path, 0, "", "cannot read measured run: not an HDF5 file" + hdf5_reason());
  try {
    const Handle file = own(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open file");
    return read_hdf5(path, file, std::filesystem::file_size(path));
  } catch (const Failure& e) {
    throw InputError(path, 0, "", std::string("cannot read measured run: ") + e.what());
  }
}

namespace {
void write_atomically(const std::string& path, const MeasuredRun& run,
                      const std::vector<std::pair<std::string, double>>& number_attributes) {
  write_file_atomically(path, "measured run", [&](const std::string& tmp) { write_file(tmp, run, number_attributes); });
}
}  // namespace

void write_measured_run_hdf5(const std::string& path, const MeasuredRun& run) {
  validate_for_writing(path, run);
  write_atomically(path, run, {});
}

namespace detail {
void write_measured_run_hdf5_unchecked(const std::string& path, const MeasuredRun& run,
                                       const std::vector<std::pair<std::string, double>>& number_attributes) {
  write_atomically(path, run, number_attributes);
}
}  // namespace detail

}  // namespace shudder::io
