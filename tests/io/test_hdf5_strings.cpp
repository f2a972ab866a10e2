// The shared HDF5 layer's two layouts of a fixed-length string (io/include/sedwave/io/hdf5.hpp): packing,
// run and checkpoint files store a string's bytes exactly, table files add a terminating NUL. Each
// is read back whole by the one reader, whichever layout wrote it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sedwave/io/hdf5.hpp"

namespace sedwave::io {
namespace {

/// A file that lives in memory only (HDF5's core driver without a backing store).
Handle memory_file() {
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access properties");
  check(H5Pset_fapl_core(access, 1 << 16, false), "keep the file in memory");
  return {H5Fcreate("strings.h5", H5F_ACC_TRUNC, H5P_DEFAULT, access), H5Fclose, "create a file in memory"};
}

std::size_t attribute_bytes(hid_t parent, const std::string& name) {
  Handle attribute(H5Aopen(parent, name.c_str(), H5P_DEFAULT), H5Aclose, "open attribute " + name);
  Handle type(H5Aget_type(attribute), H5Tclose, "attribute type");
  return H5Tget_size(type);
}

const std::vector<std::string> kValues{"", "a", "sedwave dispersion table", std::string(300, 'x')};

TEST(Hdf5Strings, ExactLayoutStoresTheBytesAndReadsBack) {
  const Handle file = memory_file();
  for (std::size_t k = 0; k < kValues.size(); ++k) {
    const std::string name = "exact" + std::to_string(k);
    write_string_attribute(file, name, kValues[k], StringBytes::exact);
    EXPECT_EQ(attribute_bytes(file, name), std::max<std::size_t>(kValues[k].size(), 1));
    EXPECT_EQ(read_string_attribute(file, name), kValues[k]);
  }
}

TEST(Hdf5Strings, NulTerminatedLayoutAddsOneByteAndReadsBack) {
  const Handle file = memory_file();
  for (std::size_t k = 0; k < kValues.size(); ++k) {
    const std::string name = "terminated" + std::to_string(k);
    write_string_attribute(file, name, kValues[k], StringBytes::nul_terminated);
    EXPECT_EQ(attribute_bytes(file, name), kValues[k].size() + 1);
    EXPECT_EQ(read_string_attribute(file, name), kValues[k]);
  }
}

TEST(Hdf5Strings, StringDatasetsReadBackInBothLayouts) {
  const Handle file = memory_file();
  for (const StringBytes layout : {StringBytes::exact, StringBytes::nul_terminated}) {
    for (std::size_t k = 0; k < kValues.size(); ++k) {
      const std::string name = "set" + std::to_string(static_cast<int>(layout)) + "_" + std::to_string(k);
      write_string_dataset(file, name, kValues[k], layout);
      EXPECT_EQ(read_string_dataset(file, name), kValues[k]);
    }
  }
}

TEST(Hdf5Strings, ANumberIsNotReadAsAString) {
  const Handle file = memory_file();
  write_attribute(file, "count", std::int32_t{3});
  EXPECT_THROW((void)read_string_attribute(file, "count"), std::runtime_error);
}

}  // namespace
}  // namespace sedwave::io
