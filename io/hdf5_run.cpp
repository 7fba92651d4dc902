// Run output <-> HDF5 (layout in hdf5_run.hpp). HDF5 C API through hdf5_util's RAII handles;
// the library's automatic error printing is switched off while we work and its innermost error
// message is attached to the InputError instead.
#include "io/hdf5_run.hpp"

#include <hdf5.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "io/hdf5_util.hpp"
#include "io/input_error.hpp"

namespace shudder::io {

using namespace hdf5;

namespace {

using dynamics::Recording;

// This file's own failures share the helpers' type: one catch converts both to InputError.
using Failure = hdf5::Error;

// ---- writing -------------------------------------------------------------------------------

// Links a group keeps in its object header (compact storage) before HDF5 moves them to dense
// storage (a fractal heap and two B-trees, for names and creation order). The run file's groups
// hold tens of links (≤ 27 in the shipped runs): kept compact, creating them costs ≈ 0.3 ms less
// per `shudder run` (Case 1, docs/performance.md), and readers list them in creation order all
// the same (HDF5 sorts a compact group's links by the tracked order). Larger groups go dense,
// and back to compact below 48.
constexpr unsigned kMaxCompactLinks = 64;

// A group whose links remember creation order, so readers can return them in write order.
Handle make_group(hid_t parent, const std::string& name) {
  const Handle gcpl = own(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "create property list");
  ok(H5Pset_link_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), "track creation order");
  ok(H5Pset_link_phase_change(gcpl, kMaxCompactLinks, kMaxCompactLinks * 3 / 4), "set compact link storage");
  return own(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose, "create group '" + name + "'");
}

// Datasets of at least this many values (512 kB) are chunked and compressed; below it deflate
// saves little on disk but much time: Paper G Case 1 (15 signals x 1001 samples) took 193 kB
// stored plain and 134 kB deflated, and the deflate cost ~13 M instructions, a tenth of the
// whole `shudder run` (docs/performance.md). Long runs (10 kHz rig runs, 10^5+ samples) are
// still compressed.
constexpr hsize_t kCompressFromValues = 65536;
// Values per chunk, at most: 2^14 doubles = 128 kB, inside HDF5's advice of 10 kB–1 MB per
// chunk and its 1 MB default chunk cache, so a reader decompresses each chunk once.
constexpr hsize_t kChunkValues = 16384;
// zlib level 4: h5py's default; levels above it cost time for a few per cent.
constexpr unsigned kDeflateLevel = 4;

// Dataset creation properties: contiguous for small data; otherwise chunked along the first
// axis (whole rows of the others), byte-shuffled (the exponent bytes of neighbouring samples
// agree, which deflate then finds) and deflated. Readers need nothing: HDF5 decompresses.
Handle creation_properties(const std::vector<hsize_t>& dims, hsize_t count, bool compress) {
  // Contiguous: the library's default list, which is not ours to close (a list of our own per
  // dataset cost a create and a close each, ≈ 2 % of a short run).
  if (!compress || dims.empty() || count < kCompressFromValues)
    return Handle(H5P_DEFAULT, [](hid_t) -> herr_t { return 0; });
  Handle dcpl = own(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create dataset properties");
  const hsize_t row = count / dims.front();  // values per index of the first axis
  std::vector<hsize_t> chunk = dims;
  chunk.front() = std::max<hsize_t>(1, std::min(dims.front(), kChunkValues / std::max<hsize_t>(row, 1)));
  ok(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), "set chunk shape");
  ok(H5Pset_shuffle(dcpl), "set shuffle filter");
  ok(H5Pset_deflate(dcpl, kDeflateLevel), "set deflate filter");
  return dcpl;
}

// A double dataset of shape `dims` (empty = scalar), row-major `data`, with a `units` attribute.
void write_doubles(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims, const double* data,
                   const std::string& units, bool compress = true) {
  const Handle space = dims.empty() ? own(H5Screate(H5S_SCALAR), H5Sclose, "create dataspace")
                                    : own(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                                          H5Sclose, "create dataspace for '" + name + "'");
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  const Handle dcpl = creation_properties(dims, count, compress);
  const Handle dset = own(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                          H5Dclose, "create dataset '" + name + "'");
  if (count > 0)
    ok(H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write dataset '" + name + "'");
  write_string_attr(dset, "units", units);
}

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Checks everything that can be checked before touching the disk.
void validate(const std::string& path, const Recording& rec) {
  const auto bad = [&](const std::string& key, const std::string& msg) { throw InputError(path, 0, key, msg); };
  const auto check_names = [&](const auto& items, const char* what) {
    std::set<std::string> seen;
    for (const auto& item : items) {
      if (item.name.empty() || item.name == "." || item.name.find('/') != std::string::npos)
        bad(item.name, std::string(what) + " name must be non-empty and contain no '/'");
      if (!seen.insert(item.name).second) bad(item.name, std::string("duplicate ") + what);
    }
  };
  check_names(rec.signals, "signal");
  check_names(rec.scalars, "scalar");
  for (const auto& s : rec.signals)
    if (s.values.size() != rec.signals.front().values.size())
      bad(s.name, "signal has " + std::to_string(s.values.size()) + " samples but '" + rec.signals.front().name +
                      "' has " + std::to_string(rec.signals.front().values.size()) +
                      "; all signals must have the same length");
  check_names(rec.maps, "map");
  for (const auto& m : rec.maps) {
    const std::string where = "analysis/" + m.name;
    if (m.name == "summary") bad(where, "map name 'summary' is taken by the summary scalars");
    // Dataset names inside the map's group: grid axes, layers and scalars, all distinct.
    std::set<std::string> names;
    const auto dataset_name = [&](const std::string& n, const char* what) {
      if (n.empty() || n == "." || n.find('/') != std::string::npos)
        bad(where, std::string(what) + " name '" + n + "' must be non-empty and contain no '/'");
      if (!names.insert(n).second) bad(where, "duplicate dataset name '" + n + "'");
    };
    dataset_name(m.x_name, "x axis");
    dataset_name(m.y_name, "y axis");
    for (const auto& l : m.layers) dataset_name(l.name, "layer");
    for (const auto& sc : m.scalars) dataset_name(sc.name, "scalar");
    for (const auto* axis : {&m.x, &m.y})
      if (axis->empty()) bad(where, "map axes must have at least one value");
    if (m.layers.empty()) bad(where, "a map needs at least one layer of values");
    for (const auto& l : m.layers)
      if (l.values.rows() != static_cast<long>(m.x.size()) || l.values.cols() != static_cast<long>(m.y.size()))
        bad(where + "/" + l.name, "layer is " + std::to_string(l.values.rows()) + " x " +
                                      std::to_string(l.values.cols()) + " but the grid is " +
                                      std::to_string(m.x.size()) + " (" + m.x_name + ") x " +
                                      std::to_string(m.y.size()) + " (" + m.y_name + ")");
  }
  // Result blocks share /analysis with the summary and the maps.
  check_names(rec.blocks, "result block");
  for (const auto& b : rec.blocks) {
    const std::string where = "analysis/" + b.name;
    if (b.name == "summary" || rec.find_map(b.name)) bad(where, "result block name is taken by the summary or a map");
    std::set<std::string> datasets, texts{"description"};
    for (const auto& sc : b.scalars)
      if (sc.name.empty() || sc.name == "." || sc.name.find('/') != std::string::npos ||
          !datasets.insert(sc.name).second)
        bad(where, "scalar name '" + sc.name + "' must be non-empty, unique and contain no '/'");
    for (const auto& t : b.texts)
      if (t.name.empty() || !texts.insert(t.name).second)
        bad(where, "text name '" + t.name + "' must be non-empty, unique and not 'description'");
  }
  for (const auto& snap : rec.snapshots) {
    const auto& first = rec.snapshots.front().temp_C;
    if (snap.temp_C.rows() != first.rows() || snap.temp_C.cols() != first.cols())
      bad("thermal/temp_C", "snapshots differ in shape; all must be (n_z x n_r)");
    if ((!rec.grid_z_m.empty() && snap.temp_C.rows() != static_cast<long>(rec.grid_z_m.size())) ||
        (!rec.grid_r_m.empty() && snap.temp_C.cols() != static_cast<long>(rec.grid_r_m.size())))
      bad("thermal/temp_C", "snapshot shape " + std::to_string(snap.temp_C.rows()) + " x " +
                                std::to_string(snap.temp_C.cols()) + " does not match grid " +
                                std::to_string(rec.grid_z_m.size()) + " (z) x " + std::to_string(rec.grid_r_m.size()) +
                                " (r)");
  }
}

void write_thermal(hid_t file, const Recording& rec) {
  if (rec.grid_r_m.empty() && rec.grid_z_m.empty() && rec.snapshots.empty()) return;
  const Handle thermal = make_group(file, "thermal");
  if (!rec.grid_r_m.empty()) write_doubles(thermal, "r_m", {rec.grid_r_m.size()}, rec.grid_r_m.data(), "m");
  if (!rec.grid_z_m.empty()) write_doubles(thermal, "z_m", {rec.grid_z_m.size()}, rec.grid_z_m.data(), "m");
  if (rec.snapshots.empty()) return;
  // Flatten to (n_snap x n_z x n_r), row-major (Eigen's own storage is column-major).
  const auto n_snap = rec.snapshots.size();
  const auto n_z = static_cast<std::size_t>(rec.snapshots.front().temp_C.rows());
  const auto n_r = static_cast<std::size_t>(rec.snapshots.front().temp_C.cols());
  std::vector<double> times(n_snap), temps(n_snap * n_z * n_r);
  for (std::size_t k = 0; k < n_snap; ++k) {
    times[k] = rec.snapshots[k].time_s;
    for (std::size_t i = 0; i < n_z; ++i)
      for (std::size_t j = 0; j < n_r; ++j)
        temps[(k * n_z + i) * n_r + j] = rec.snapshots[k].temp_C(static_cast<long>(i), static_cast<long>(j));
  }
  write_doubles(thermal, "times_s", {n_snap}, times.data(), "s");
  write_doubles(thermal, "temp_C", {n_snap, n_z, n_r}, temps.data(), "degC");
}

// One map as /analysis/<name>/: the two axes (1-D), each layer (n_x x n_y, row-major) and the
// map's scalars, each with `units`; group attributes `x`, `y` name the axis datasets.
void write_map(hid_t analysis, const dynamics::Map2D& m) {
  const Handle group = make_group(analysis, m.name);
  write_string_attr(group, "description", m.description);
  write_string_attr(group, "x", m.x_name);
  write_string_attr(group, "y", m.y_name);
  write_doubles(group, m.x_name, {m.x.size()}, m.x.data(), m.x_units);
  write_doubles(group, m.y_name, {m.y.size()}, m.y.data(), m.y_units);
  for (const auto& l : m.layers) {
    // Eigen stores column-major; the file is row-major (n_x x n_y).
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = l.values;
    write_doubles(group, l.name, {m.x.size(), m.y.size()}, rows.data(), l.units);
  }
  for (const auto& s : m.scalars) write_doubles(group, s.name, {}, &s.value, s.units);
}

// One result block as /analysis/<name>/: each scalar a dataset with `units`, each text and the
// description a string attribute of the group.
void write_block(hid_t analysis, const dynamics::ResultBlock& b) {
  const Handle group = make_group(analysis, b.name);
  write_string_attr(group, "description", b.description);
  for (const auto& t : b.texts) write_string_attr(group, t.name, t.value);
  for (const auto& sc : b.scalars) write_doubles(group, sc.name, {}, &sc.value, sc.units);
}

void write_file(const std::string& file_name, const Recording& rec, const std::string& scenario,
                const std::string& fluid, bool compress_signals) {
  Handle file = own(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                    "create file '" + file_name + "'");
  {
    // Signals: all the same length (validated).
    const Handle signals = make_group(file, "signals");
    for (const auto& s : rec.signals)
      write_doubles(signals, s.name, {s.values.size()}, s.values.data(), s.units, compress_signals);
    write_thermal(file, rec);
    // Summary scalars, result blocks and maps.
    if (!rec.scalars.empty() || !rec.blocks.empty() || !rec.maps.empty()) {
      const Handle analysis = make_group(file, "analysis");
      if (!rec.scalars.empty()) {
        const Handle summary = make_group(analysis, "summary");
        for (const auto& s : rec.scalars) write_doubles(summary, s.name, {}, &s.value, s.units);
      }
      for (const auto& b : rec.blocks) write_block(analysis, b);
      for (const auto& m : rec.maps) write_map(analysis, m);
    }
    // Root attributes.
    write_string_attr(file, "scenario", scenario);
    // The fluid file's text beside the scenario's: the file alone reproduces the run.
    if (!fluid.empty()) write_string_attr(file, "fluid", fluid);
    write_string_attr(file, "shudder_version", SHUDDER_VERSION);
    write_string_attr(file, "created_utc", utc_now_iso8601());
  }
  ok(file.close(), "close (flush) file '" + file_name + "'");
}

// ---- reading -------------------------------------------------------------------------------

bool has_link(hid_t parent, const std::string& name) {
  const htri_t exists = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  ok(exists, "look up '" + name + "'");
  return exists > 0;
}

std::optional<std::string> read_string_attr(hid_t obj, const std::string& name) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  ok(exists, "look up attribute '" + name + "'");
  if (exists == 0) return std::nullopt;
  const Handle attr = own(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute '" + name + "'");
  const Handle file_type = own(H5Aget_type(attr), H5Tclose, "read type of '" + name + "'");
  if (H5Tget_class(file_type) != H5T_STRING) throw Failure("attribute '" + name + "' is not a string");
  return read_string_value(attr, file_type, name);
}

struct Array {
  std::vector<hsize_t> dims;
  std::vector<double> values;  // row-major
  std::string units;
};

Array read_doubles(hid_t parent, const std::string& name) {
  const Handle dset = own(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset '" + name + "'");
  {
    const Handle type = own(H5Dget_type(dset), H5Tclose, "read type of '" + name + "'");
    const H5T_class_t cls = H5Tget_class(type);
    if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw Failure("dataset '" + name + "' is not numeric");
  }
  const Handle space = own(H5Dget_space(dset), H5Sclose, "read shape of '" + name + "'");
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) throw Failure("cannot read shape of '" + name + "'" + hdf5_reason());
  Array a;
  a.dims.resize(static_cast<std::size_t>(rank));
  if (rank > 0) ok(H5Sget_simple_extent_dims(space, a.dims.data(), nullptr), "read shape of '" + name + "'");
  hsize_t count = 1;
  for (hsize_t d : a.dims) count *= d;
  a.values.resize(count);
  if (count > 0)
    ok(H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.values.data()), "read dataset '" + name + "'");
  a.units = read_string_attr(dset, "units").value_or("");
  return a;
}

void read_signals(hid_t file, Recording& rec) {
  if (!has_link(file, "signals")) throw Failure("no /signals group; not a shudder run file");
  const Handle group = own(H5Gopen2(file, "signals", H5P_DEFAULT), H5Gclose, "open /signals");
  for (const auto& name : link_names(group)) {
    Array a = read_doubles(group, name);
    if (a.dims.size() != 1) throw Failure("signal '" + name + "' is not 1-D");
    if (!rec.signals.empty() && a.values.size() != rec.signals.front().values.size())
      throw Failure("signal '" + name + "' has " + std::to_string(a.values.size()) + " samples but '" +
                    rec.signals.front().name + "' has " + std::to_string(rec.signals.front().values.size()));
    rec.signals.push_back({name, std::move(a.units), std::move(a.values)});
  }
  std::stable_partition(rec.signals.begin(), rec.signals.end(),
                        [](const dynamics::Signal& s) { return s.name == "time_s"; });
}

void read_thermal(hid_t file, Recording& rec) {
  if (!has_link(file, "thermal")) return;
  const Handle group = own(H5Gopen2(file, "thermal", H5P_DEFAULT), H5Gclose, "open /thermal");
  if (has_link(group, "r_m")) rec.grid_r_m = read_doubles(group, "r_m").values;
  if (has_link(group, "z_m")) rec.grid_z_m = read_doubles(group, "z_m").values;
  if (!has_link(group, "temp_C")) return;
  if (!has_link(group, "times_s")) throw Failure("/thermal/temp_C without /thermal/times_s");
  const std::vector<double> times = read_doubles(group, "times_s").values;
  const Array temps = read_doubles(group, "temp_C");
  if (temps.dims.size() != 3 || temps.dims[0] != times.size())
    throw Failure("/thermal/temp_C must be (n_snap x n_z x n_r) with n_snap = size of times_s");
  const std::size_t n_z = temps.dims[1], n_r = temps.dims[2];
  for (std::size_t k = 0; k < times.size(); ++k) {
    // Row-major (n_snap x n_z x n_r) -> one (n_z x n_r) matrix per snapshot.
    const double* first = temps.values.data() + k * n_z * n_r;
    dynamics::ThermalSnapshot snap{times[k], Eigen::MatrixXd(n_z, n_r)};
    for (std::size_t i = 0; i < n_z; ++i)
      for (std::size_t j = 0; j < n_r; ++j)
        snap.temp_C(static_cast<long>(i), static_cast<long>(j)) = first[i * n_r + j];
    rec.snapshots.push_back(std::move(snap));
  }
}

void read_scalars(hid_t file, Recording& rec) {
  if (!has_link(file, "analysis")) return;
  const Handle analysis = own(H5Gopen2(file, "analysis", H5P_DEFAULT), H5Gclose, "open /analysis");
  if (!has_link(analysis, "summary")) return;
  const Handle summary = own(H5Gopen2(analysis, "summary", H5P_DEFAULT), H5Gclose, "open /analysis/summary");
  for (const auto& name : link_names(summary)) {
    Array a = read_doubles(summary, name);
    if (a.values.size() != 1) throw Failure("summary value '" + name + "' is not a scalar");
    rec.scalars.push_back({name, std::move(a.units), a.values.front()});
  }
}

// Names of the attributes of `obj`, in name order.
std::vector<std::string> attribute_names(hid_t obj, const std::string& where) {
  std::vector<std::string> names;
  hsize_t next = 0;
  ok(H5Aiterate2(
         obj, H5_INDEX_NAME, H5_ITER_INC, &next,
         [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
           static_cast<std::vector<std::string>*>(out)->emplace_back(name);
           return 0;
         },
         &names),
     "list attributes of " + where);
  return names;
}

// A group under /analysis without the map attributes, read as a result block (write_block):
// its scalar numeric datasets and its string attributes; anything else in it is skipped.
dynamics::ResultBlock read_block(hid_t group, const std::string& name) {
  const std::string where = "/analysis/" + name;
  dynamics::ResultBlock b;
  b.name = name;
  for (const auto& attr : attribute_names(group, where)) {
    {
      const Handle a = own(H5Aopen(group, attr.c_str(), H5P_DEFAULT), H5Aclose, "open attribute '" + attr + "'");
      const Handle type = own(H5Aget_type(a), H5Tclose, "read type of '" + attr + "'");
      if (H5Tget_class(type) != H5T_STRING) continue;
    }
    std::string value = read_string_attr(group, attr).value_or("");
    if (attr == "description")
      b.description = std::move(value);
    else
      b.texts.push_back({attr, std::move(value)});
  }
  for (const auto& dname : link_names(group)) {
    const Handle obj = own(H5Oopen(group, dname.c_str(), H5P_DEFAULT), H5Oclose, "open " + where + "/" + dname);
    if (H5Iget_type(obj) != H5I_DATASET) continue;
    const Handle type = own(H5Dget_type(obj), H5Tclose, "read type of '" + dname + "'");
    const H5T_class_t cls = H5Tget_class(type);
    if (cls != H5T_FLOAT && cls != H5T_INTEGER) continue;
    Array a = read_doubles(group, dname);
    if (a.dims.empty()) b.scalars.push_back({dname, std::move(a.units), a.values.front()});
  }
  return b;
}

// Every group under /analysis carrying the `x` and `y` attributes is a map (write_map); every
// other group but the summary is a result block (write_block).
void read_maps(hid_t file, Recording& rec) {
  if (!has_link(file, "analysis")) return;
  const Handle analysis = own(H5Gopen2(file, "analysis", H5P_DEFAULT), H5Gclose, "open /analysis");
  for (const auto& name : link_names(analysis)) {
    if (name == "summary") continue;
    {
      const Handle obj = own(H5Oopen(analysis, name.c_str(), H5P_DEFAULT), H5Oclose, "open /analysis/" + name);
      if (H5Iget_type(obj) != H5I_GROUP) continue;
    }
    const Handle group = own(H5Gopen2(analysis, name.c_str(), H5P_DEFAULT), H5Gclose, "open /analysis/" + name);
    const auto x_name = read_string_attr(group, "x"), y_name = read_string_attr(group, "y");
    if (!x_name || !y_name) {
      rec.blocks.push_back(read_block(group, name));
      continue;
    }
    const std::string where = "/analysis/" + name;
    dynamics::Map2D m;
    m.name = name;
    m.description = read_string_attr(group, "description").value_or("");
    m.x_name = *x_name;
    m.y_name = *y_name;
    for (const auto* axis : {&m.x_name, &m.y_name})
      if (!has_link(group, *axis)) throw Failure(where + ": axis dataset '" + *axis + "' missing");
    Array x = read_doubles(group, m.x_name), y = read_doubles(group, m.y_name);
    if (x.dims.size() != 1 || y.dims.size() != 1) throw Failure(where + ": map axes must be 1-D");
    m.x = std::move(x.values);
    m.x_units = std::move(x.units);
    m.y = std::move(y.values);
    m.y_units = std::move(y.units);
    for (const auto& dname : link_names(group)) {
      if (dname == m.x_name || dname == m.y_name) continue;
      Array a = read_doubles(group, dname);
      if (a.dims.empty()) {
        m.scalars.push_back({dname, std::move(a.units), a.values.front()});
        continue;
      }
      if (a.dims.size() != 2 || a.dims[0] != m.x.size() || a.dims[1] != m.y.size())
        throw Failure(where + "/" + dname + ": a map layer must be (n_x x n_y) = (" + std::to_string(m.x.size()) +
                      " x " + std::to_string(m.y.size()) + ")");
      // Row-major (n_x x n_y) in the file.
      m.layers.push_back({dname, std::move(a.units),
                          Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
                              a.values.data(), static_cast<long>(a.dims[0]), static_cast<long>(a.dims[1]))});
    }
    rec.maps.push_back(std::move(m));
  }
}

// Opens `path` read-only after checking it exists and is HDF5; throws InputError otherwise.
Handle open_for_reading(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, 0, "", "cannot read run file: no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0)
    throw InputError(path, 0, "", "cannot read run file: not an HDF5 file" + hdf5_reason());
  try {
    return own(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open file");
  } catch (const Failure& e) {
    throw InputError(path, 0, "", e.what());
  }
}

}  // namespace

void write_run_hdf5(const std::string& path, const Recording& rec, const std::string& scenario_text,
                    const std::string& fluid_text, RunCompression compression) {
  validate(path, rec);
  const bool deflate = compression == RunCompression::kDeflate;
  write_file_atomically(path, "run file",
                        [&](const std::string& tmp) { write_file(tmp, rec, scenario_text, fluid_text, deflate); });
}

Recording read_run_hdf5(const std::string& path) {
  const std::lock_guard lock(hdf5_mutex());
  const QuietHdf5 quiet;
  const Handle file = open_for_reading(path);
  Recording rec;
  try {
    read_signals(file, rec);
    read_thermal(file, rec);
    read_scalars(file, rec);
    read_maps(file, rec);
  } catch (const Failure& e) {
    throw InputError(path, 0, "", e.what());
  }
  return rec;
}

std::string read_run_attribute(const std::string& path, const std::string& name) {
  const std::lock_guard lock(hdf5_mutex());
  const QuietHdf5 quiet;
  const Handle file = open_for_reading(path);
  try {
    return read_string_attr(file, name).value_or("");
  } catch (const Failure& e) {
    throw InputError(path, 0, "", e.what());
  }
}

namespace detail {
long open_hdf5_identifiers() {
  const QuietHdf5 quiet;
  long total = 0;
  for (H5I_type_t type : {H5I_FILE, H5I_GROUP, H5I_DATATYPE, H5I_DATASPACE, H5I_DATASET, H5I_ATTR, H5I_GENPROP_LST}) {
    hsize_t n = 0;
    if (H5Inmembers(type, &n) >= 0) total += static_cast<long>(n);
  }
  H5Eclear2(H5E_DEFAULT);
  return total;
}
}  // namespace detail

}  // namespace shudder::io

// ---- sweeps ----------------------------------------------------------------------------------

#include "io/hdf5_sweep.hpp"

namespace shudder::io {

namespace {

void write_strings(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
  const Handle type = vlen_string_type();
  const hsize_t n = values.size();
  const Handle space = own(H5Screate_simple(1, &n, nullptr), H5Sclose, "create dataspace for '" + name + "'");
  const Handle dset = own(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                          H5Dclose, "create dataset '" + name + "'");
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  if (n > 0) ok(H5Dwrite(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()), "write dataset '" + name + "'");
}

void write_sweep_file(const std::string& file_name, const SweepOutput& sw) {
  Handle file = own(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                    "create file '" + file_name + "'");
  {
    const Handle cases = make_group(file, "cases");
    for (const auto& c : sw.columns) write_doubles(cases, c.name, {c.values.size()}, c.values.data(), c.units);
    write_strings(cases, sw.text_column_name, sw.text_column);
    write_strings(cases, kSweepMessageColumn, sw.message_column);
    const bool from_parts = !sw.case_part_paths.empty();
    const std::size_t n_cases = from_parts ? sw.case_part_paths.size() : sw.case_recordings.size();
    for (std::size_t k = 0; k < n_cases; ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "case_%05zu", k);
      const Handle group = make_group(file, name);
      const Handle signals = make_group(group, "signals");
      Recording part;  // one part's signals at a time (the caller holds the HDF5 mutex)
      if (from_parts && !sw.case_part_paths[k].empty()) {
        const Handle in = open_for_reading(sw.case_part_paths[k]);
        read_signals(in, part);
      }
      for (const auto& s : from_parts ? part.signals : sw.case_recordings[k].signals)
        write_doubles(signals, s.name, {s.values.size()}, s.values.data(), s.units);
      if (k < sw.case_scenarios.size()) write_string_attr(group, "scenario", sw.case_scenarios[k]);
    }
    write_string_attr(file, "scenario", sw.base_scenario_text);
    if (!sw.fluid_text.empty()) write_string_attr(file, "fluid", sw.fluid_text);
    write_string_attr(file, "shudder_version", SHUDDER_VERSION);
    write_string_attr(file, "created_utc", utc_now_iso8601());
  }
  ok(file.close(), "close (flush) file '" + file_name + "'");
}

}  // namespace

void write_sweep_hdf5(const std::string& path, const SweepOutput& sweep) {
  const std::size_t n = sweep.text_column.size();
  if (sweep.message_column.size() != n)
    throw InputError(path, 0, "",
                     "sweep message column has " + std::to_string(sweep.message_column.size()) + " rows, expected " +
                         std::to_string(n));
  for (const auto& c : sweep.columns)
    if (c.values.size() != n)
      throw InputError(path, 0, "",
                       "sweep column '" + c.name + "' has " + std::to_string(c.values.size()) + " rows, expected " +
                           std::to_string(n));
  write_file_atomically(path, "sweep file", [&](const std::string& tmp) { write_sweep_file(tmp, sweep); });
}

void write_failed_case_part(const std::string& path, const std::string& scenario_text, const std::string& message) {
  write_file_atomically(path, "sweep part", [&](const std::string& tmp) {
    Handle file =
        own(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, "create file '" + tmp + "'");
    write_string_attr(file, "scenario", scenario_text);
    write_string_attr(file, kSweepMessageColumn, message);
    write_string_attr(file, "shudder_version", SHUDDER_VERSION);
    ok(file.close(), "close (flush) file '" + tmp + "'");
  });
}

}  // namespace shudder::io

namespace shudder::io {

namespace {

std::vector<std::string> read_strings(hid_t parent, const std::string& name) {
  const Handle dset = own(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "open dataset '" + name + "'");
  const Handle space = own(H5Dget_space(dset), H5Sclose, "read shape of '" + name + "'");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0) throw Failure("cannot read shape of '" + name + "'");
  const Handle type = vlen_string_type();
  std::vector<char*> raw(static_cast<std::size_t>(n), nullptr);
  if (n > 0) ok(H5Dread(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), "read dataset '" + name + "'");
  std::vector<std::string> out;
  for (char* p : raw) out.emplace_back(p ? p : "");
  if (n > 0) H5Dvlen_reclaim(type, space, H5P_DEFAULT, raw.data());
  return out;
}

}  // namespace

SweepTable read_sweep_table(const std::string& path) {
  const std::lock_guard lock(hdf5_mutex());
  const QuietHdf5 quiet;
  const Handle file = open_for_reading(path);
  try {
    if (!has_link(file, "cases")) throw Failure("no /cases group: not a sweep file");
    const Handle cases = own(H5Gopen2(file, "cases", H5P_DEFAULT), H5Gclose, "open /cases");
    SweepTable t;
    for (const auto& name : link_names(cases)) {
      const Handle dset = own(H5Dopen2(cases, name.c_str(), H5P_DEFAULT), H5Dclose, "open '" + name + "'");
      const Handle type = own(H5Dget_type(dset), H5Tclose, "read type of '" + name + "'");
      if (H5Tget_class(type) == H5T_STRING && name == kSweepMessageColumn) {
        t.message_column = read_strings(cases, name);
      } else if (H5Tget_class(type) == H5T_STRING) {
        t.text_column_name = name;
        t.text_column = read_strings(cases, name);
      } else {
        Array a = read_doubles(cases, name);
        t.columns.push_back({name, a.units, std::move(a.values)});
      }
    }
    return t;
  } catch (const Failure& e) {
    throw InputError(path, 0, "", std::string("cannot read sweep file: ") + e.what());
  }
}

}  // namespace shudder::io
