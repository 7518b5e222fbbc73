// The HDF5 layer of the raw-data file: property lists, attributes, dimension scales and types.
#include "raw_hdf5.hpp"

#include <hdf5_hl.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fogradar::experiment::detail {
namespace {

// A scalar attribute stored as `file_type`, written from `value` of `memory_type`.
void scalar_attribute(hid_t object, const char* name, hid_t file_type, hid_t memory_type,
                      const void* value) {
  const Handle space(checked(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
  const Handle attribute(
      checked(H5Acreate2(object, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              "H5Acreate2"),
      H5Aclose);
  checked(H5Awrite(attribute.get(), memory_type, value), "H5Awrite");
}

}  // namespace

Handle property_list(hid_t cls) { return {checked(H5Pcreate(cls), "H5Pcreate"), H5Pclose}; }

Handle untimed(hid_t cls) {
  Handle list = property_list(cls);
  checked(H5Pset_obj_track_times(list.get(), false), "H5Pset_obj_track_times");
  return list;
}

void string_attribute(hid_t object, const char* name, const std::string& value) {
  const Handle type(checked(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  checked(H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1)), "H5Tset_size");
  checked(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  const Handle space(checked(H5Screate(H5S_SCALAR), "H5Screate"), H5Sclose);
  const Handle attribute(
      checked(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              "H5Acreate2"),
      H5Aclose);
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  checked(H5Awrite(attribute.get(), type.get(), padded.data()), "H5Awrite");
}

void number_attribute(hid_t object, const char* name, double value) {
  scalar_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void integer_attribute(hid_t object, const char* name, std::int64_t value) {
  scalar_attribute(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

// A 1-D dataset made a dimension scale named `name`.
Handle scale(hid_t group, const std::string& name, hid_t file_type, hid_t memory_type,
             const void* values, hsize_t count, const std::string& units) {
  const Handle space(checked(H5Screate_simple(1, &count, nullptr), "H5Screate_simple"), H5Sclose);
  const Handle create = untimed(H5P_DATASET_CREATE);
  Handle dataset(checked(H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                    create.get(), H5P_DEFAULT),
                         "H5Dcreate2"),
                 H5Dclose);
  if (count > 0) {
    checked(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values),
            "H5Dwrite");
  }
  checked(H5DSset_scale(dataset.get(), name.c_str()), "H5DSset_scale");
  if (!units.empty()) string_attribute(dataset.get(), "units", units);
  return dataset;
}

// {r, i} doubles: the layout of std::complex<double>, which h5py reads as complex128.
Handle complex_type(hid_t part) {
  Handle type(checked(H5Tcreate(H5T_COMPOUND, 16), "H5Tcreate"), H5Tclose);
  checked(H5Tinsert(type.get(), "r", 0, part), "H5Tinsert");
  checked(H5Tinsert(type.get(), "i", 8, part), "H5Tinsert");
  return type;
}

// An 8-bit enumeration over `base` (H5T_STD_U8LE in the file, H5T_NATIVE_UINT8 in memory): each
// label named with its index as value.
Handle enum_type(hid_t base, const std::vector<std::string>& labels) {
  Handle type(checked(H5Tenum_create(base), "H5Tenum_create"), H5Tclose);
  for (std::size_t v = 0; v < labels.size(); ++v) {
    const auto value = static_cast<std::uint8_t>(v);
    checked(H5Tenum_insert(type.get(), labels[v].c_str(), &value), "H5Tenum_insert");
  }
  return type;
}

}  // namespace fogradar::experiment::detail
