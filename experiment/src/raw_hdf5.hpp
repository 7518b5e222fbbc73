// The HDF5 layer of the raw-data file (raw_file.cpp): handles, errors, attributes, scales, types.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace fogradar::experiment::detail {

// Closes an HDF5 identifier with its own close function.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = other.id_;
      close_ = other.close_;
      other.id_ = -1;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  // Closes now; false when the close failed (a full disk shows up when the file is closed).
  bool close() {
    const bool ok = id_ < 0 || close_(id_) >= 0;
    id_ = -1;
    return ok;
  }

 private:
  void reset() {
    if (id_ >= 0) close_(id_);
    id_ = -1;
  }
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

class Hdf5Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// hid_t (an identifier) and herr_t (a status) are distinct integer types: one overload each.
inline hid_t checked(hid_t id, const char* what) {
  if (id < 0) throw Hdf5Error(what);
  return id;
}
inline void checked(herr_t status, const char* what) {
  if (status < 0) throw Hdf5Error(what);
}

Handle property_list(hid_t cls);

// Group and dataset creation without modification times, so the same run gives the same bytes.
Handle untimed(hid_t cls);

void string_attribute(hid_t object, const char* name, const std::string& value);
void number_attribute(hid_t object, const char* name, double value);
void integer_attribute(hid_t object, const char* name, std::int64_t value);

// A 1-D dataset made a dimension scale named `name`.
Handle scale(hid_t group, const std::string& name, hid_t file_type, hid_t memory_type,
             const void* values, hsize_t count, const std::string& units);

// {r, i} doubles: the layout of std::complex<double>, which h5py reads as complex128.
Handle complex_type(hid_t part);

// An 8-bit enumeration over `base` (H5T_STD_U8LE in the file, H5T_NATIVE_UINT8 in memory): each
// label named with its index as value.
Handle enum_type(hid_t base, const std::vector<std::string>& labels);

}  // namespace fogradar::experiment::detail
