#pragma once
#include <hdf5.h>

#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "parallel/Communicator.hpp"

namespace rondel {

// A parallel HDF5 file opened collectively by every rank of a communicator, with the few operations the
// checkpoint and snapshot layers need. Datasets are 1D (n) or 2D (n x 2) arrays; each rank writes or reads
// a contiguous block of rows [offset, offset + count) collectively. Errors name the file: IoError when
// creating or writing fails, InputError when a file read is missing, damaged or not what was expected.
//
// Errors are agreed (parallel/Agreement.hpp), so a failure on one rank throws on every rank and none is
// left waiting: reads settle their outcome among the ranks at once; a failed group or attribute write is
// kept and settled with the next dataset write (whose checksum reduction carries a failure count: one
// collective per dataset) or when run() ends. The file is closed (collectively) by run(), close() or the
// destructor on a normal exit; a destructor that runs during an exception calls nothing collective (the
// file is left to the HDF5 library's clean-up at exit), so a rank that unwinds alone never blocks in it.
//
// A file being written is made known good or removed: its space is reserved first (`reserve_bytes`, when
// the file system can: a full disk or a quota is then found before HDF5 writes anything, instead of in the
// middle of a collective write, where some MPI-IO layers report it on one rank only or not at all); its
// metadata is flushed, checked and agreed before the close, whose result is checked too; a file whose
// writing failed is emptied (its space given back, so that the close's own writes fit) and removed.
class Hdf5File {
 public:
  enum class Mode { create, read };
  // `reserve_bytes` (create only): the space to reserve, an estimate from above (0: none).
  Hdf5File(const std::string& path, Mode mode, const Communicator& comm, std::uint64_t reserve_bytes = 0);
  ~Hdf5File();
  // Collective: settles the errors kept, flushes a written file (checked), then closes it (checked;
  // idempotent). A written file that fails here is removed.
  void close();
  // Keeps an error of this rank (e.g. an allocation that failed while preparing a block) to be thrown on
  // every rank at the next dataset write or when run() ends; not collective.
  void defer_error(std::exception_ptr error) {
    if (!kept_) kept_ = std::move(error);
  }
  // Runs f() and closes the file, also when f throws: f's errors must be agreed ones (thrown on every rank,
  // as this class's are), so that every rank closes.
  template <class F>
  void run(F&& f) {
    try {
      f();
      close();
    } catch (...) {
      abandon();
      throw;
    }
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  const std::string& path() const { return path_; }
  void create_group(const std::string& name);
  bool exists(const std::string& name) const;

  // Attributes on an object ("/" for the file). Every rank passes the same value.
  void write_attribute(const std::string& object, const std::string& name, const std::string& value);
  void write_attribute(const std::string& object, const std::string& name, std::int64_t value);
  void write_attribute(const std::string& object, const std::string& name, double value);
  std::string read_string_attribute(const std::string& object, const std::string& name) const;
  std::int64_t read_int_attribute(const std::string& object, const std::string& name) const;
  double read_double_attribute(const std::string& object, const std::string& name) const;
  bool has_attribute(const std::string& object, const std::string& name) const;

  // Collective block write: `total` rows of `width` values; this rank's rows start at `offset`.
  template <class T>
  void write(const std::string& name, const std::vector<T>& local, std::uint64_t total, std::uint64_t offset,
             int width = 1) {
    write_block(name, local.data(), local.size(), total, offset, width);
  }
  // The same from `values` elements of T at `local` (a reused buffer).
  template <class T>
  void write_block(const std::string& name, const T* local, std::uint64_t values, std::uint64_t total,
                   std::uint64_t offset, int width = 1);
  // The same for a dataset of one T a row, written in collective pieces of at most `piece` rows (every rank makes
  // as many writes as the rank with the most pieces): fill(first, n) returns this rank's rows [first, first + n)
  // of its block (a buffer of the caller's, reused from piece to piece).
  template <class T>
  void write_pieces(const std::string& name, std::uint64_t rows, std::uint64_t total, std::uint64_t offset,
                    std::uint64_t piece, const std::function<const T*(std::uint64_t, std::uint64_t)>& fill);
  // Collective block read of rows [offset, offset + count). Every dataset carries a checksum of its rows
  // (order-independent, so it does not depend on how the rows were split over ranks); it is verified
  // after reading: `partitioned` when the ranks' blocks cover the dataset once, otherwise (every rank reads
  // the whole dataset) each rank checks its own copy. A mismatch is an InputError naming the file.
  template <class T>
  std::vector<T> read(const std::string& name, std::uint64_t offset, std::uint64_t count, int width = 1,
                      bool partitioned = true) const;
  // Rows of a dataset (0 when absent).
  std::uint64_t rows(const std::string& name) const;

  // Every object below the root, depth first in name order: (path, true for a dataset, false for a group).
  std::vector<std::pair<std::string, bool>> objects() const;
  // The checksum of the attributes (FORMAT.md "attributes_checksum"): the wrapping sum, over every attribute
  // of every object but /integrity's `attributes_checksum` and the root's `complete`, of a mix of the FNV-1a hash of
  // "object path \0 name \0 value as stored". Collective only in that a failure is agreed.
  std::uint64_t attribute_digest() const;
  // The checksum of a dataset (FORMAT.md "checksum") of `rows` rows of `row_bytes` bytes each, from `bytes`.
  static std::uint64_t dataset_checksum(const void* bytes, std::size_t row_bytes, std::uint64_t rows);
  // Collective: reads this rank's block of dataset `name` (any type this class writes) and verifies its
  // checksum; `rows` is the count it must have. InputError on every rank otherwise.
  void verify_dataset(const std::string& name, std::uint64_t rows) const;

 private:
  // Collective: throws on every rank (InputError, or IoError when `writing`) if `ok` is false on any, or
  // if any rank kept an error (that one then).
  void check(bool ok, const std::string& what, bool writing = false) const;
  // write_block and write_pieces: `n_local` rows of `width` T each.
  template <class T>
  void write_rows(const std::string& name, std::uint64_t n_local, std::uint64_t total, std::uint64_t offset, int width,
                  std::uint64_t piece, const std::function<const T*(std::uint64_t, std::uint64_t)>& fill);
  // Keeps the first failure of this rank for the next settlement (not collective).
  void keep(bool ok, const std::string& what);
  // Collective: every rank throws the kept error of the lowest failing rank, if any.
  void settle_kept();
  // Collective, after an agreed error: closes without checking; a written file is emptied first and removed.
  void abandon();
  void close_now();
  std::uint64_t reduce_sum(std::uint64_t local) const;
  std::string path_;
  Communicator comm_;
  bool writing_ = false;
  hid_t file_ = -1;
  hid_t xfer_ = -1;
  std::exception_ptr kept_;
};

}  // namespace rondel
