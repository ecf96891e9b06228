#include "parallel/Hdf5File.hpp"

#include <cstring>
#include <exception>
#include <type_traits>

#include "core/ContactTable.hpp"
#include "core/Errors.hpp"
#include "core/Vec2.hpp"
#include "parallel/Agreement.hpp"

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
std::uint64_t row_hash(const unsigned char* row, std::size_t row_bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (std::size_t b = 0; b < row_bytes; ++b) h = (h ^ row[b]) * 0x100000001b3ULL;
  return h;
}
std::uint64_t row_checksum(const char* bytes, std::size_t row_bytes, std::uint64_t rows, std::uint64_t first) {
  // FNV-1a is one chain of multiplies per row: eight rows at a time keep the multiplier busy (the same
  // value as one row after the other; the sum does not depend on the order).
  constexpr std::uint64_t kLanes = 8;
  const auto* p = reinterpret_cast<const unsigned char*>(bytes);
  std::uint64_t sum = 0, r = 0;
  for (; r + kLanes <= rows; r += kLanes) {
    std::uint64_t h[kLanes];
    for (std::uint64_t l = 0; l < kLanes; ++l) h[l] = 0xcbf29ce484222325ULL;
    const unsigned char* row = p + r * row_bytes;
    for (std::size_t b = 0; b < row_bytes; ++b)
      for (std::uint64_t l = 0; l < kLanes; ++l) h[l] = (h[l] ^ row[l * row_bytes + b]) * 0x100000001b3ULL;
    for (std::uint64_t l = 0; l < kLanes; ++l) sum += mix(h[l] + 0x9e3779b97f4a7c15ULL * (first + r + l + 1));
  }
  for (; r < rows; ++r) sum += mix(row_hash(p + r * row_bytes, row_bytes) + 0x9e3779b97f4a7c15ULL * (first + r + 1));
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
  std::exception_ptr error;
  if (file_ < 0 && mode == Mode::create)
    error = std::make_exception_ptr(IoError("cannot create the HDF5 file '" + path + "' (is the directory writable?)"));
  else if (file_ < 0)
    error = std::make_exception_ptr(
        InputError("cannot open the HDF5 file '" + path + "' (missing, truncated or not an HDF5 file)"));
  // A rank that opened the file while another failed keeps its handle open: closing it would wait for the
  // rank that has none.
  settle(comm_, error);
  xfer_ = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(xfer_, H5FD_MPIO_COLLECTIVE);
}

Hdf5File::~Hdf5File() {
  if (std::uncaught_exceptions() == 0) close_now();
}

void Hdf5File::close() {
  settle_kept();
  close_now();
}

void Hdf5File::close_now() {
  if (xfer_ >= 0) H5Pclose(xfer_);
  xfer_ = -1;
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
}

std::uint64_t Hdf5File::reduce_sum(std::uint64_t local) const {
  std::uint64_t out = local;
  if (comm_.size() > 1) MPI_Allreduce(&local, &out, 1, MPI_UINT64_T, MPI_SUM, comm_.comm());
  return out;
}

void Hdf5File::keep(bool ok, const std::string& what) {
  if (!ok && !kept_) kept_ = std::make_exception_ptr(IoError("HDF5 file '" + path_ + "': " + what));
}

void Hdf5File::settle_kept() {
  std::exception_ptr error = kept_;
  kept_ = nullptr;
  settle(comm_, error);
}

void Hdf5File::check(bool ok, const std::string& what, bool writing) const {
  std::exception_ptr error = kept_;
  const std::string message = "HDF5 file '" + path_ + "': " + what;
  if (!ok && !error)
    error = writing ? std::make_exception_ptr(IoError(message)) : std::make_exception_ptr(InputError(message));
  settle(comm_, error);
}

void Hdf5File::create_group(const std::string& name) {
  Handle g{H5Gcreate2(file_, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose};
  keep(g.id >= 0, "cannot create group " + name);
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
  keep(attr.id >= 0 && H5Awrite(attr.id, type.id, padded.data()) >= 0, "cannot write attribute " + name);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate_by_name(file_, object.c_str(), name.c_str(), H5T_STD_I64LE, space.id, H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT),
              H5Aclose};
  keep(attr.id >= 0 && H5Awrite(attr.id, H5T_NATIVE_INT64, &value) >= 0, "cannot write attribute " + name);
}

void Hdf5File::write_attribute(const std::string& object, const std::string& name, double value) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate_by_name(file_, object.c_str(), name.c_str(), H5T_IEEE_F64LE, space.id, H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT),
              H5Aclose};
  keep(attr.id >= 0 && H5Awrite(attr.id, H5T_NATIVE_DOUBLE, &value) >= 0, "cannot write attribute " + name);
}

bool Hdf5File::has_attribute(const std::string& object, const std::string& name) const {
  return H5Aexists_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string Hdf5File::read_string_attribute(const std::string& object, const std::string& name) const {
  Handle attr{H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  check(attr.id >= 0, "has no attribute " + object + ":" + name);
  Handle type{H5Aget_type(attr.id), H5Tclose};
  check(H5Tget_class(type.id) == H5T_STRING, "attribute " + name + " is not a string");
  const std::size_t size = H5Tget_size(type.id);
  std::string value(size, '\0');
  Handle mem{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(mem.id, size);
  H5Tset_strpad(mem.id, H5T_STR_NULLPAD);
  check(H5Aread(attr.id, mem.id, value.data()) >= 0, "cannot read attribute " + name);
  value.resize(std::strlen(value.c_str()));
  return value;
}

std::int64_t Hdf5File::read_int_attribute(const std::string& object, const std::string& name) const {
  Handle attr{H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  std::int64_t v = 0;
  check(attr.id >= 0 && H5Aread(attr.id, H5T_NATIVE_INT64, &v) >= 0, "has no integer attribute " + object + ":" + name);
  return v;
}

double Hdf5File::read_double_attribute(const std::string& object, const std::string& name) const {
  Handle attr{H5Aopen_by_name(file_, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  double v = 0;
  check(attr.id >= 0 && H5Aread(attr.id, H5T_NATIVE_DOUBLE, &v) >= 0, "has no number attribute " + object + ":" + name);
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
void Hdf5File::write_block(const std::string& name, const T* local, std::uint64_t values, std::uint64_t total,
                           std::uint64_t offset, int width) {
  width *= components<T>();
  const int rank = width == 1 ? 1 : 2;
  hsize_t dims[2] = {total, static_cast<hsize_t>(width)};
  Handle space{H5Screate_simple(rank, dims, nullptr), H5Sclose};
  Handle set{H5Dcreate2(file_, name.c_str(), memory_type<T>(), space.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose};
  const hsize_t n_local = values * components<T>() / width;
  // Agreed before the collective write, which a rank with a bad selection would not join.
  check(set.id >= 0 && offset + n_local <= total,
        set.id < 0 ? "cannot create dataset " + name
                   : "rows [" + std::to_string(offset) + ", " + std::to_string(offset + n_local) +
                         ") are outside dataset " + name + " of " + std::to_string(total) + " rows",
        true);
  hsize_t start[2] = {offset, 0}, count[2] = {n_local, static_cast<hsize_t>(width)};
  H5Sselect_hyperslab(space.id, H5S_SELECT_SET, start, nullptr, count, nullptr);
  Handle mem{H5Screate_simple(rank, count, nullptr), H5Sclose};
  if (n_local == 0) H5Sselect_none(mem.id), H5Sselect_none(space.id);
  if (total > 0)
    keep(H5Dwrite(set.id, memory_type<T>(), mem.id, space.id, xfer_, local) >= 0, "cannot write dataset " + name);
  // One reduction: the checksum and the number of ranks that failed so far.
  std::uint64_t sums[2] = {
      row_checksum(reinterpret_cast<const char*>(local), width / components<T>() * sizeof(T), n_local, offset),
      kept_ ? 1u : 0u};
  if (comm_.size() > 1) MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_UINT64_T, MPI_SUM, comm_.comm());
  if (sums[1] > 0) settle_kept();
  Handle scalar{H5Screate(H5S_SCALAR), H5Sclose};
  Handle attr{H5Acreate2(set.id, "checksum", H5T_STD_U64LE, scalar.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  keep(attr.id >= 0 && H5Awrite(attr.id, H5T_NATIVE_UINT64, &sums[0]) >= 0, "cannot write the checksum of " + name);
}

template <class T>
std::vector<T> Hdf5File::read(const std::string& name, std::uint64_t offset, std::uint64_t count, int width,
                              bool partitioned) const {
  width *= components<T>();
  Handle set{H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose};
  check(set.id >= 0, "has no dataset " + name);
  Handle space{H5Dget_space(set.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  hsize_t dims[2] = {0, 1};
  H5Sget_simple_extent_dims(space.id, dims, nullptr);
  check(!((width == 1 && rank != 1) || (width > 1 && (rank != 2 || dims[1] != static_cast<hsize_t>(width))) ||
          offset + count > dims[0]),
        "dataset " + name + " has an unexpected shape");
  std::vector<T> out(count * width / components<T>());
  hsize_t start[2] = {offset, 0}, cnt[2] = {count, static_cast<hsize_t>(width)};
  H5Sselect_hyperslab(space.id, H5S_SELECT_SET, start, nullptr, cnt, nullptr);
  Handle mem{H5Screate_simple(rank, cnt, nullptr), H5Sclose};
  if (count == 0) H5Sselect_none(mem.id), H5Sselect_none(space.id);
  check(dims[0] == 0 || H5Dread(set.id, memory_type<T>(), mem.id, space.id, xfer_, out.data()) >= 0,
        "cannot read dataset " + name);
  const std::uint64_t local =
      row_checksum(reinterpret_cast<const char*>(out.data()), width / components<T>() * sizeof(T), count, offset);
  const std::uint64_t sum = partitioned ? reduce_sum(local) : local;
  std::uint64_t stored = 0;
  Handle attr{H5Aopen(set.id, "checksum", H5P_DEFAULT), H5Aclose};
  check(attr.id >= 0 && H5Aread(attr.id, H5T_NATIVE_UINT64, &stored) >= 0, "dataset " + name + " has no checksum");
  check(stored == sum, "dataset " + name + " fails its checksum: the file is corrupted");
  return out;
}

#define RONDEL_HDF5_TYPE(T)                                                                                            \
  template void Hdf5File::write_block(const std::string&, const T*, std::uint64_t, std::uint64_t, std::uint64_t, int); \
  template std::vector<T> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
RONDEL_HDF5_TYPE(double)
RONDEL_HDF5_TYPE(Vec2)
RONDEL_HDF5_TYPE(std::int64_t)
RONDEL_HDF5_TYPE(std::int32_t)
RONDEL_HDF5_TYPE(std::uint32_t)
RONDEL_HDF5_TYPE(ContactKey)
#undef RONDEL_HDF5_TYPE

}  // namespace rondel
