#pragma once
// Test support: after an edit of a closed Rondel file that stands for what a writer meant (not a corruption),
// its attributes' checksum (FORMAT.md "attributes_checksum") made to fit.
#include <hdf5.h>
#include <mpi.h>

#include <cstdint>
#include <filesystem>

#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"

namespace rondel::test {

inline void restamp(const std::filesystem::path& file) {
  std::uint64_t digest = 0;
  {
    const Hdf5File f(file.string(), Hdf5File::Mode::read, Communicator(MPI_COMM_SELF));
    digest = f.attribute_digest();
  }
  // The object held open while its attribute is written (HDF5 1.10 cannot write one opened by path).
  const hid_t f = H5Fopen(file.string().c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t o = H5Oopen(f, "/integrity", H5P_DEFAULT);
  const hid_t a = H5Aopen(o, "attributes_checksum", H5P_DEFAULT);
  const auto stamp = static_cast<std::int64_t>(digest);
  H5Awrite(a, H5T_NATIVE_INT64, &stamp);
  H5Aclose(a);
  H5Oclose(o);
  H5Fclose(f);
}

}  // namespace rondel::test
