#include "parallel/Hdf5File.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <type_traits>

#include "core/ContactTable.hpp"
#include "core/Errors.hpp"
#include "core/FaultInjection.hpp"
#include "core/FileSpace.hpp"
#include "core/InputFile.hpp"
#include "core/Vec2.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/CanonicalOrder.hpp"

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

// The objects below a group, depth first (H5Literate's callback).
struct Walk {
  std::string prefix;
  std::vector<std::pair<std::string, bool>>* out;
};
herr_t walk_link(hid_t group, const char* name, const H5L_info_t*, void* data) {
  const auto* walk = static_cast<const Walk*>(data);
  Handle object{H5Oopen(group, name, H5P_DEFAULT), H5Oclose};
  if (object.id < 0) return -1;
  const std::string path = (walk->prefix == "/" ? "/" : walk->prefix + "/") + name;  // HDF5's root group
  const H5I_type_t type = H5Iget_type(object.id);
  walk->out->emplace_back(path, type == H5I_DATASET);
  if (type != H5I_GROUP) return 0;
  Walk inner{path, walk->out};
  return H5Literate(object.id, H5_INDEX_NAME, H5_ITER_INC, nullptr, walk_link, &inner) < 0 ? -1 : 0;
}

// The attributes of one object, hashed into `sum` (H5Aiterate2's callback).
struct Digest {
  std::string object;
  std::uint64_t sum = 0;
};
herr_t digest_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  auto* d = static_cast<Digest*>(data);
  const std::string n = name;
  // The two attributes written after the checksum is taken (FORMAT.md, "attributes_checksum").
  if ((d->object == "/" && n == "complete") || (d->object == "/integrity" && n == "attributes_checksum")) return 0;
  Handle attr{H5Aopen(object, name, H5P_DEFAULT), H5Aclose};
  if (attr.id < 0) return -1;
  Handle type{H5Aget_type(attr.id), H5Tclose};
  std::string bytes = d->object + '\0' + n + '\0';
  const std::size_t head = bytes.size(), size = H5Aget_storage_size(attr.id);
  bytes.resize(head + size);
  if (type.id < 0 || (size > 0 && H5Aread(attr.id, type.id, bytes.data() + head) < 0)) return -1;
  d->sum += mix(row_hash(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()) + 0x9e3779b97f4a7c15ULL);
  return 0;
}

}  // namespace

Hdf5File::Hdf5File(const std::string& path, Mode mode, const Communicator& comm, std::uint64_t reserve_bytes)
    : path_(path), comm_(comm.comm()), writing_(mode == Mode::create) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions with the file's name
  if (writing_) injected_fault_new_file(comm_.rank());
  const bool reserve = writing_ && reserve_bytes > 0 && comm_.root();
  const bool injected = reserve && injected_fault(FaultSite::reserve, comm_.rank());
  std::exception_ptr error;
  // Before HDF5 writes anything: a disk without the room is found here, and nothing is left behind.
  if (reserve) {
    const std::string why = reserve_file_space(path, reserve_bytes, injected);
    if (!why.empty()) {
      std::remove(path.c_str());
      error = std::make_exception_ptr(IoError("not enough space to write '" + path + "': " + why));
    }
  }
  // A FIFO or a device would block the open or be read without end: only a regular file is opened to read.
  const FileKind kind = writing_ ? FileKind::regular : file_kind(path);
  if (kind != FileKind::regular && kind != FileKind::missing)
    error = std::make_exception_ptr(InputError(input_file_problem(path, "the HDF5 file")));
  settle(comm_, error);
  Handle fapl{H5Pcreate(H5P_FILE_ACCESS), H5Pclose};
  H5Pset_fapl_mpio(fapl.id, comm.comm(), MPI_INFO_NULL);
  file_ = writing_ ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id)
                   : H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.id);
  if (file_ < 0 && writing_)
    error = std::make_exception_ptr(IoError("cannot create the HDF5 file '" + path + "' (is the directory writable?)"));
  else if (file_ < 0)
    error = std::make_exception_ptr(
        InputError("cannot open the HDF5 file '" + path + "' (missing, truncated or not an HDF5 file)"));
  // A rank that opened the file while another failed keeps its handle open: closing it would wait for the
  // rank that has none. The space reserved for a file that could not be created goes.
  try {
    settle(comm_, error);
  } catch (...) {
    if (reserve) std::remove(path.c_str());
    throw;
  }
  xfer_ = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(xfer_, H5FD_MPIO_COLLECTIVE);
  // The create emptied the file: reserved again, for the writes to come.
  if (reserve) {
    const std::string why = reserve_file_space(path, reserve_bytes, injected);
    if (!why.empty()) error = std::make_exception_ptr(IoError("not enough space to write '" + path + "': " + why));
  }
  try {
    settle(comm_, error);
  } catch (...) {
    abandon();
    throw;
  }
}

Hdf5File::~Hdf5File() {
  if (std::uncaught_exceptions() == 0) close_now();
}

void Hdf5File::close() {
  try {
    settle_kept();
    // The metadata reaches the file here, where a failure can still be agreed; the close then has nothing
    // left to write (a close that fails leaves HDF5 with a file it can neither use nor forget).
    if (writing_ && file_ >= 0)
      check(H5Fflush(file_, H5F_SCOPE_GLOBAL) >= 0 && !injected_fault(FaultSite::hdf5_close, comm_.rank()),
            "cannot write its metadata (disk full?)", true);
  } catch (...) {
    abandon();
    throw;
  }
  if (xfer_ >= 0) H5Pclose(xfer_);
  xfer_ = -1;
  const bool closed = file_ < 0 || H5Fclose(file_) >= 0;
  file_ = -1;
  if (!writing_) return;
  writing_ = false;
  std::exception_ptr error;
  if (!closed) error = std::make_exception_ptr(IoError("HDF5 file '" + path_ + "': cannot close it (disk full?)"));
  try {
    settle(comm_, error);
  } catch (...) {
    if (comm_.root()) std::remove(path_.c_str());
    throw;
  }
}

void Hdf5File::abandon() {
  // Every rank is here (the error was agreed). Emptying the file gives its space back, so that what the close
  // still writes (the superblock, the metadata) fits on a disk that the file itself filled.
  if (writing_ && comm_.root() && file_ >= 0 && ::truncate(path_.c_str(), 0) != 0) {
    // nothing more to do: the close below may fail, the file is removed anyway
  }
  close_now();
  if (writing_ && comm_.root()) std::remove(path_.c_str());
  writing_ = false;
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

std::vector<std::pair<std::string, bool>> Hdf5File::objects() const {
  std::vector<std::pair<std::string, bool>> out;
  Walk root{"/", &out};
  check(H5Literate(file_, H5_INDEX_NAME, H5_ITER_INC, nullptr, walk_link, &root) >= 0, "cannot list its objects");
  return out;
}

std::uint64_t Hdf5File::dataset_checksum(const void* bytes, std::size_t row_bytes, std::uint64_t rows) {
  return row_checksum(static_cast<const char*>(bytes), row_bytes, rows, 0);
}

std::uint64_t Hdf5File::attribute_digest() const {
  std::uint64_t sum = 0;
  std::vector<std::string> paths{"/"};
  for (const auto& [path, dataset] : objects()) paths.push_back(path);
  bool ok = true;
  for (const std::string& path : paths) {
    Handle object{H5Oopen(file_, path.c_str(), H5P_DEFAULT), H5Oclose};
    Digest d{path, 0};
    ok = ok && object.id >= 0 && H5Aiterate2(object.id, H5_INDEX_NAME, H5_ITER_INC, nullptr, digest_attribute, &d) >= 0;
    sum += d.sum;
  }
  check(ok, "cannot read its attributes");
  return sum;
}

void Hdf5File::verify_dataset(const std::string& name, std::uint64_t rows) const {
  Handle set{H5Dopen2(file_, name.c_str(), H5P_DEFAULT), H5Dclose};
  check(set.id >= 0, "has no dataset " + name);
  Handle type{H5Dget_type(set.id), H5Tclose};
  Handle space{H5Dget_space(set.id), H5Sclose};
  const int dims_n = H5Sget_simple_extent_ndims(space.id);
  hsize_t dims[2] = {0, 1};
  const bool shaped = dims_n == 1 || dims_n == 2;
  if (shaped) H5Sget_simple_extent_dims(space.id, dims, nullptr);
  check(shaped && dims[0] == rows, "dataset " + name + " has " + std::to_string(dims[0]) +
                                       " rows where its group has " + std::to_string(rows) + ": the file is damaged");
  const H5T_class_t cls = H5Tget_class(type.id);
  const std::size_t size = H5Tget_size(type.id);
  const bool is_signed = cls == H5T_INTEGER && H5Tget_sign(type.id) == H5T_SGN_2;
  const std::uint64_t begin = block_begin(rows, comm_.rank(), comm_.size());
  const std::uint64_t count = block_begin(rows, comm_.rank() + 1, comm_.size()) - begin;
  const int width = static_cast<int>(dims[1]);
  if (cls == H5T_FLOAT && size == 8)
    read<double>(name, begin, count, width);
  else if (cls == H5T_INTEGER && size == 8 && is_signed)
    read<std::int64_t>(name, begin, count, width);
  else if (cls == H5T_INTEGER && size == 4 && is_signed)
    read<std::int32_t>(name, begin, count, width);
  else if (cls == H5T_INTEGER && size == 4)
    read<std::uint32_t>(name, begin, count, width);
  else
    check(false, "dataset " + name + " has an element type that Rondel does not write");
}

template <class T>
void Hdf5File::write_block(const std::string& name, const T* local, std::uint64_t values, std::uint64_t total,
                           std::uint64_t offset, int width) {
  const std::uint64_t rows = values * components<T>() / (width * components<T>());
  write_rows<T>(name, rows, total, offset, width, total, [local, width](std::uint64_t first, std::uint64_t) {
    return local + first * static_cast<std::uint64_t>(width);
  });
}

template <class T>
void Hdf5File::write_pieces(const std::string& name, std::uint64_t rows, std::uint64_t total, std::uint64_t offset,
                            std::uint64_t piece, const std::function<const T*(std::uint64_t, std::uint64_t)>& fill) {
  write_rows<T>(name, rows, total, offset, 1, piece, fill);
}

template <class T>
void Hdf5File::write_rows(const std::string& name, std::uint64_t n_local, std::uint64_t total, std::uint64_t offset,
                          int width, std::uint64_t piece,
                          const std::function<const T*(std::uint64_t, std::uint64_t)>& fill) {
  const std::size_t row_bytes = static_cast<std::size_t>(width) * sizeof(T);
  width *= components<T>();
  const int rank = width == 1 ? 1 : 2;
  hsize_t dims[2] = {total, static_cast<hsize_t>(width)};
  Handle space{H5Screate_simple(rank, dims, nullptr), H5Sclose};
  Handle set{H5Dcreate2(file_, name.c_str(), memory_type<T>(), space.id, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             H5Dclose};
  // Agreed before the collective write, which a rank with a bad selection would not join.
  check(set.id >= 0 && offset + n_local <= total,
        set.id < 0 ? "cannot create dataset " + name
                   : "rows [" + std::to_string(offset) + ", " + std::to_string(offset + n_local) +
                         ") are outside dataset " + name + " of " + std::to_string(total) + " rows",
        true);
  // Every rank makes the same number of collective writes (an empty one when its block is done).
  std::uint64_t pieces = total == 0 ? 0 : 1;
  if (piece < total) {
    pieces = (n_local + piece - 1) / piece;
    if (comm_.size() > 1) MPI_Allreduce(MPI_IN_PLACE, &pieces, 1, MPI_UINT64_T, MPI_MAX, comm_.comm());
  }
  std::uint64_t sums[2] = {0, 0};
  for (std::uint64_t p = 0; p < pieces; ++p) {
    const std::uint64_t first = std::min(p * piece, n_local), n = std::min(piece, n_local - first);
    const T* data = n > 0 ? fill(first, n) : nullptr;
    Handle slab{H5Dget_space(set.id), H5Sclose};
    hsize_t start[2] = {offset + first, 0}, count[2] = {n, static_cast<hsize_t>(width)};
    H5Sselect_hyperslab(slab.id, H5S_SELECT_SET, start, nullptr, count, nullptr);
    Handle mem{H5Screate_simple(rank, count, nullptr), H5Sclose};
    if (n == 0) H5Sselect_none(mem.id), H5Sselect_none(slab.id);
    keep(H5Dwrite(set.id, memory_type<T>(), mem.id, slab.id, xfer_, data) >= 0 &&
             !injected_fault(FaultSite::hdf5_write, comm_.rank()),
         "cannot write dataset " + name);
    sums[0] += row_checksum(reinterpret_cast<const char*>(data), row_bytes, n, offset + first);
  }
  // One reduction: the checksum and the number of ranks that failed so far.
  sums[1] = kept_ ? 1u : 0u;
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
  template void Hdf5File::write_pieces(const std::string&, std::uint64_t, std::uint64_t, std::uint64_t, std::uint64_t, \
                                       const std::function<const T*(std::uint64_t, std::uint64_t)>&);                  \
  template std::vector<T> Hdf5File::read(const std::string&, std::uint64_t, std::uint64_t, int, bool) const;
RONDEL_HDF5_TYPE(double)
RONDEL_HDF5_TYPE(Vec2)
RONDEL_HDF5_TYPE(std::int64_t)
RONDEL_HDF5_TYPE(std::int32_t)
RONDEL_HDF5_TYPE(std::uint32_t)
RONDEL_HDF5_TYPE(ContactKey)
#undef RONDEL_HDF5_TYPE

}  // namespace rondel
