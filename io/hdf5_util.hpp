#pragma once
// What the HDF5 readers and writers in io/ share: RAII handles for the HDF5 C API, turning its
// failures into an Error whose text names the step and HDF5's own reason, and the one mutex
// every HDF5 call in this library holds, because the Debian libhdf5 is not thread-safe. Only
// for io/*.cpp: it includes <hdf5.h>, which is on shudder_io's private include path.

#include <hdf5.h>

#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shudder::io::hdf5 {

/// Thrown by the helpers below as "cannot <what> (HDF5: <reason>)". Callers throw it for their
/// own content errors too, so one catch at the public edge turns both into an InputError.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Hold for every HDF5 call, from any thread (sweeps write from workers).
std::mutex& hdf5_mutex();

/// Owns one hid_t and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), close_(o.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  operator hid_t() const { return id_; }  // NOLINT: implicit, so handles pass straight to H5*
  /// Closes now and reports failure (closing a file flushes it: errors matter there).
  herr_t close() { return id_ >= 0 ? close_(std::exchange(id_, H5I_INVALID_HID)) : 0; }

 private:
  hid_t id_;
  Closer close_;
};

/// Switches HDF5's automatic error printing off for its lifetime, restoring it afterwards: the
/// reason goes into our error message instead of onto stderr.
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

/// " (HDF5: <most specific message on the error stack>)", or "" if the stack is empty; clears
/// the stack.
std::string hdf5_reason();

/// `id` as a Handle; Error "cannot <what>..." if it is negative (the call failed).
Handle own(hid_t id, Handle::Closer close, const std::string& what);

/// Error "cannot <what>..." if `status` is negative.
void ok(herr_t status, const std::string& what);

/// Link names in creation order when the group tracks it (our writers), else in name order
/// (e.g. files from h5py).
std::vector<std::string> link_names(hid_t group);

/// Variable-length UTF-8 string type, so h5py reads our strings as str.
Handle vlen_string_type();

/// A scalar attribute `name` = `value` on `obj`, as a vlen_string_type().
void write_string_attr(hid_t obj, const std::string& name, const std::string& value);

/// The value of the open scalar string attribute `attr` whose type is `file_type`, variable-
/// or fixed-length (other tools write the latter); `name` is for messages.
std::string read_string_value(hid_t attr, hid_t file_type, const std::string& name);

/// Builds an HDF5 file with `write(tmp)` under a temporary name, holding the mutex with HDF5's
/// own error printing off, and renames it to `path` when complete (no half-written file). An
/// Error from `write` becomes the InputError "cannot write <what>: <reason>; check the directory
/// exists and is writable"; anything else passes through; either way the temporary is removed.
void write_file_atomically(const std::string& path, const std::string& what,
                           const std::function<void(const std::string& tmp)>& write);

}  // namespace shudder::io::hdf5
