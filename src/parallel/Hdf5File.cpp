#include "parallel/Hdf5File.hpp"

#include <cstring>
#include <type_traits>

#include "core/ContactTable.hpp"
#include "core/Errors.hpp"
#include "core/Vec2.hpp"

namespace rondel {

namespace {

template <class T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, Vec2>)
    return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, std::int64_t> || std::is_same_v<T, ContactKey>)
    return H5T_NATIVE_INT64;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return H5T_NATIVE_INT32;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return H5T_NATIVE_UINT32;
  else
    static_assert(sizeof(T) == 0, "unsupported HDF5 element type");
}

// Values per row of T in memory (a Vec2 or a ContactKey is two numbers).
template <class T>
constexpr int components() {
  return (std::is_same_v<T, Vec2> || std::is_same_v<T, ContactKey>) ? 2 : 1;
}

// Order-independent checksum of rows: the wrapping sum over rows of a mix of the row's global index and
// the FNV-1a hash of its bytes.
std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
std::uint64_t row_checksum(const char* bytes, std::size_t row_bytes, std::uint64_t rows, std::uint64_t first) {
  std::uint64_t sum = 0;
  for (std::uint64_t r = 0; r < rows; ++r) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (std::size_t b = 0; b < row_bytes; ++b)
      h = (h ^ static_cast<unsigned char>(bytes[r * row_bytes + b])) * 0x100000001b3ULL;
    sum += mix(h + 0x9e3779b97f4a7c15ULL * (first + r + 1));
  }
  return sum;
}

struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

}  // namespace

Hdf5File::Hdf5File(const std::string& path, Mode mode, const Communicator& comm) : path_(path), comm_(comm.comm()) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions with the file's name
  Handle fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
  H5Pset_fapl_mpio(fapl.id, comm.comm(), MPI_INFO_NULL);
  file_ = mode == Mode::create ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id)
                               : H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.id);
  if (file_ < 0)
    throw InputError(
        std::string(mode == Mode::create ? "cannot create" : "cannot open") + " the HDF5 file '" + path + "'" +
        (mode == Mode::read ? " (missing, truncated or not an HDF5 file)" : " (is the directory writable?)"));
  xfer_ = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(xfer_, H5FD_MPIO_COLLECTIVE);
}

Hdf5File::~Hdf5File() {
  if (xfer_ >= 0) H5Pclose(xfer_);
  if (file_ >= 0) H5Fclose(file_);
}

std::uint64_t Hdf5File::reduce_sum(std::uint64_t local) const {
  std::uint64_t out = 0;
  MPI_Allreduce(&local, &out, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return out;
}

void Hdf5File::fail(const std::string& what) const { throw InputError("HDF5 file '" + path_ + "': " + what); }

void Hdf5File::create_group(const std::string& name) {
  Handle g{H5Gcreate2(file_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
  if (g.id < 0) fail("cannot create group " + name);
}

bool Hdf5File::exists(const std::string& name) const { return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0; }

void Hdf5File::write_attribute(const std::string& object, const std::string& name, const std::string& value) {
  Handle type{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(type.id, value.empty() ? 1 : value.size());
  H5Tset_strpad(type.id, H5T_STR_NULLPAD);
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{
      H5Acreate_by_name(file_, object.c_str(), name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose};
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  if (attr.id < 0 || H5Awrite(attr.id, type.id, padded.data()) < 0) fail("cannot write attribute " + name);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate_by_name(file_, object.c_str(), name.c_str(), H5T_STD_I64LE, space.id, H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT),
              H5Aclose};
  if (attr.id < 0 || H5Awrite(attr.id, H5T_NATIVE_INT64, &value) < 0) fail("cannot write attribute " + name);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, double value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate_by_name(file_, object.c_str(), name.c_str(), H5T_IEEE_F64LE, space.id, H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT),
              H5Aclose};
  if (attr.id < 0 || H5Awrite(attr.id, H5T_NATIVE_DOUBLE, &value) < 0) fail("cannot write attribute " + name);
}

bool Hdf5File::has_attribute(const std::string& object, const std::string& name) const {
  return H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string Hdf5File::read_string_attribute(const std::string& object, const std::string& name) const {
  Handle attr{H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (attr.id < 0) fail("has no attribute " + object + ":" + name);
  Handle type{H5Aget_type(attr.id), H5Tclose};
  if (H5Tget_class(type.id) != H5T_STRING) fail("attribute " + name + " is not a string");
  const std::size_t size = H5Tget_size(type.id);
  std::string value(size, '\0');
  Handle mem{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mem.id, size);
  H5Tset_strpad(mem.id, H5T_STR_NULLPAD);
  if (H5Aread(attr.id, mem.id, value.data()) < 0) fail("cannot read attribute " + name);
  value.resize(std::strlen(value.c_str()));
  return value;
}

std::int64_t Hdf5File::read_int_attribute(const std::string& object, const std::string& name) const {
  Handle attr{H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  std::int64_t v = 0;
  if (attr.id < 0 || H5Aread(attr.id, H5T_NATIVE_INT64, &v) < 0)
    fail("has no integer attribute " + object + ":" + name);
  return v;
}

double Hdf5File::read_double_attribute(const std::string& object, const std::string& name) const {
  Handle attr{H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  double v = 0;
  if (attr.id < 0 || H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v) < 0)
    fail("has no number attribute " + object + ":" + name);
  return v;
}

std::uint64_t Hdf5File::rows(const std::string& name) const {
  if (!exists(name)) return 0;
  Handle set{H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose};
  Handle space{H5Dget_space(set.id), H5Sclose};
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space.id, dims, nullptr);
  return dims[0];
}

template <class T>
void Hdf5File::write(const std::string& name, const std::vector<T>& local, std::uint64_t total, std::uint64_t offset,
                     int width) {
  width *= components<T>();
  const int rank = width == 1 ? 1 : 2;
  hsize_t dims[2] = {total, static_cast<hsize_t>(width)};
  Handle space{H5Screate_simple(rank, dims, nullptr), H5Sclose};
  Handle set{H5Dcreate2(file_, name.c_str(), memory_type<T>(), space.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose};
  if (set.id < 0) fail("cannot create dataset " + name);
  const hsize_t n_local = local.size() * components<T>() / width;
  hsize_t start[2] = {offset, 0}, count[2] = {n_local, static_cast<hsize_t>(width)};
  H5Sselect_hyperslab(space.id, H5S_SELECT_SET, start, nullptr, count, nullptr);
  Handle mem{H5Screate_simple(rank, count, nullptr), H5Sclose};
  if (n_local == 0) H5Sselect_none(mem.id), H5Sselect_none(space.id);
  if (total > 0 && H5Dwrite(set.id, memory_type<T>(), mem.id, space.id, xfer_, local.data()) < 0)
    fail("cannot write dataset " + name);
  const std::uint64_t sum = reduce_sum(
      row_checksum(reinterpret_cast<const char*>(local.data()), width / components<T>() * sizeof(T), n_local, offset));
  Handle scalar{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate2(set.id, "checksum", H5T_STD_U64LE, scalar.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (attr.id < 0 || H5Awrite(attr.id, H5T_NATIVE_UINT64, &sum) < 0) fail("cannot write the checksum of " + name);
}

template <class T>
std::vector<T> Hdf5File::read(const std::string& name, std::uint64_t offset, std::uint64_t count, int width,
                              bool partitioned) const {
  width *= components<T>();
  Handle set{H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose};
  if (set.id < 0) fail("has no dataset " + name);
  Handle space{H5Dget_space(set.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  hsize_t dims[2] = {0, 1};
  H5Sget_simple_extent_dims(space.id, dims, nullptr);
  if ((width == 1 && rank != 1) || (width > 1 && (rank != 2 || dims[1] != static_cast<hsize_t>(width))) ||
      offset + count > dims[0])
    fail("dataset " + name + " has an unexpected shape");
  std::vector<T> out(count * width / components<T>());
  hsize_t start[2] = {offset, 0}, cnt[2] = {count, static_cast<hsize_t>(width)};
  H5Sselect_hyperslab(space.id, H5S_SELECT_SET, start, nullptr, cnt, nullptr);
  Handle mem{H5Screate_simple(rank, cnt, nullptr), H5Sclose};
  if (count == 0) H5Sselect_none(mem.id), H5Sselect_none(space.id);
  if (dims[0] > 0 && H5Dread(set.id, memory_type<T>(), mem.id, space.id, xfer_, out.data()) < 0)
    fail("cannot read dataset " + name);
  const std::uint64_t local =
      row_checksum(reinterpret_cast<const char*>(out.data()), width / components<T>() * sizeof(T), count, offset);
  const std::uint64_t sum = partitioned ? reduce_sum(local) : local;
  std::uint64_t stored = 0;
  Handle attr{H5Aopen(set.id, "checksum", H5P_DEFAULT), H5Aclose};
  if (attr.id < 0 || H5Aread(attr.id, H5T_NATIVE_UINT64, &stored) < 0) fail("dataset " + name + " has no checksum");
  if (stored != sum) fail("dataset " + name + " fails its checksum: the file is corrupted");
  return out;
}

template void Hdf5File::write(const std::string&, const std::vector<double>&, std::uint64_t, std::uint64_t, int);
template void Hdf5File::write(const std::string&, const std::vector<Vec2>&, std::uint64_t, std::uint64_t, int);
template void Hdf5File::write(const std::string&, const std::vector<std::int64_t>&, std::uint64_t, std::uint64_t, int);
template void Hdf5File::write(const std::string&, const std::vector<std::int32_t>&, std::uint64_t, std::uint64_t, int);
template void Hdf5File::write(const std::string&, const std::vector<std::uint32_t>&, std::uint64_t, std::uint64_t, int);
template void Hdf5File::write(const std::string&, const std::vector<ContactKey>&, std::uint64_t, std::uint64_t, int);
template std::vector<double> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
template std::vector<Vec2> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
template std::vector<std::int64_t> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
template std::vector<std::int32_t> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
template std::vector<std::uint32_t> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
template std::vector<ContactKey> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;

}  // namespace rondel
