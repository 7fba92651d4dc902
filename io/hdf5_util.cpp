#include "io/hdf5_util.hpp"

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

#include <cstring>

namespace shudder::io::hdf5 {

std::mutex& hdf5_mutex() {
  static std::mutex m;
  return m;
}

std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? std::string() : " (HDF5: " + reason + ")";
}

Handle own(hid_t id, Handle::Closer close, const std::string& what) {
  if (id < 0) throw Error("cannot " + what + hdf5_reason());
  return Handle(id, close);
}

void ok(herr_t status, const std::string& what) {
  if (status < 0) throw Error("cannot " + what + hdf5_reason());
}

std::vector<std::string> link_names(hid_t group) {
  H5G_info_t info;
  ok(H5Gget_info(group, &info), "read group info");
  H5_index_t index = H5_INDEX_NAME;
  {
    const Handle gcpl = own(H5Gget_create_plist(group), H5Pclose, "read group properties");
    unsigned flags = 0;
    ok(H5Pget_link_creation_order(gcpl, &flags), "read creation order");
    if (flags & H5P_CRT_ORDER_INDEXED) index = H5_INDEX_CRT_ORDER;
  }
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len = H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw Error("cannot read link name" + hdf5_reason());
    std::vector<char> buf(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, buf.data(), buf.size(), H5P_DEFAULT);
    names.emplace_back(buf.data(), static_cast<std::size_t>(len));
  }
  return names;
}

Handle vlen_string_type() {
  Handle type = own(H5Tcopy(H5T_C_S1), H5Tclose, "create string type");
  ok(H5Tset_size(type, H5T_VARIABLE), "size string type");
  ok(H5Tset_cset(type, H5T_CSET_UTF8), "set string encoding");
  return type;
}

void write_string_attr(hid_t obj, const std::string& name, const std::string& value) {
  const Handle type = vlen_string_type();
  const Handle space = own(H5Screate(H5S_SCALAR), H5Sclose, "create dataspace");
  const Handle attr = own(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                          "create attribute '" + name + "'");
  const char* text = value.c_str();
  ok(H5Awrite(attr, type, &text), "write attribute '" + name + "'");
}

std::string read_string_value(hid_t attr, hid_t file_type, const std::string& name) {
  if (H5Tis_variable_str(file_type) > 0) {
    const Handle mem_type = vlen_string_type();
    char* text = nullptr;
    ok(H5Aread(attr, mem_type, &text), "read attribute '" + name + "'");
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(file_type);
  std::vector<char> buf(size + 1, '\0');
  ok(H5Aread(attr, file_type, buf.data()), "read attribute '" + name + "'");
  return std::string(buf.data(), strnlen(buf.data(), size));
}

void write_file_atomically(const std::string& path, const std::string& what,
                           const std::function<void(const std::string& tmp)>& write) {
  const std::lock_guard lock(hdf5_mutex());
  const QuietHdf5 quiet;
  remove_stale_temp_files(path);
  const std::string tmp = temp_path_for(path);
  try {
    write(tmp);
  } catch (const Error& e) {
    discard_temp_file(tmp);
    throw InputError(path, 0, "",
                     "cannot write " + what + ": " + e.what() + "; check the directory exists and is writable");
  } catch (...) {
    discard_temp_file(tmp);
    throw;
  }
  commit_temp_file(tmp, path);
}

}  // namespace shudder::io::hdf5
