#include "parallel/OrderedText.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <new>

#include "core/Errors.hpp"
#include "core/FaultInjection.hpp"
#include "core/FileSpace.hpp"
#include "parallel/Agreement.hpp"

namespace rondel {

namespace {

// Agrees on every rank's error (settle); when there is one, the partial file goes (rank 0) before every rank throws.
void settle_or_remove(const Communicator& comm, const std::exception_ptr& error, const std::string& path) {
  try {
    settle(comm, error);
  } catch (...) {
    if (comm.root()) std::remove(path.c_str());
    throw;
  }
}
}  // namespace

void write_ordered_text(const std::string& path, const std::string& header, const CanonicalOrder& order,
                        const std::function<void(std::size_t, std::string&)>& line, const Communicator& comm,
                        std::size_t piece) {
  // Two passes over the lines: their length first (for the offsets), then the pieces written, so that no rank
  // holds more than a piece of text whatever the size of its block.
  std::string text;
  std::uint64_t length = 0;
  agree(comm, [&] {
    if (injected_fault(FaultSite::alloc, comm.rank())) throw std::bad_alloc();
    text.reserve(piece + 4096);
    length = comm.root() ? header.size() : 0;
    for (std::size_t k = 0; k < order.count(); ++k) {
      text.clear();
      line(k, text);
      length += text.size();
    }
  });
  const std::uint64_t offset = comm.exclusive_sum(length);
  const std::uint64_t total =
      comm.size() > 1 ? static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(length))) : length;
  // The whole file's space first: a full disk is found before any rank writes (a collective write that
  // fails on one rank is not reported on every rank by every MPI-IO layer).
  const std::string name = path.substr(path.find_last_of('/') + 1);
  std::exception_ptr error;
  if (comm.root()) {
    const std::string why = reserve_file_space(path, total, injected_fault(FaultSite::text, comm.rank(), name));
    if (!why.empty()) error = std::make_exception_ptr(IoError("cannot write '" + path + "': " + why));
  }
  settle_or_remove(comm, error, path);
  MPI_File file = MPI_FILE_NULL;
  int rc = MPI_File_open(comm.comm(), path.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file);
  comm.count_collective();
  if (rc != MPI_SUCCESS)
    error = std::make_exception_ptr(IoError("cannot open '" + path + "' for writing: " + mpi_error_text(rc)));
  settle_or_remove(comm, error, path);                           // every rank opened it, or every rank throws
  rc = MPI_File_set_size(file, static_cast<MPI_Offset>(total));  // what the file held before goes
  comm.count_collective();
  // Each rank writes its pieces on its own (independent writes: the ranks' piece counts differ).
  text.assign(comm.root() ? header : std::string());
  std::uint64_t at = offset;
  for (std::size_t k = 0; k <= order.count(); ++k) {
    if (k < order.count()) line(k, text);
    if (text.size() < piece && k < order.count()) continue;
    MPI_Status status;
    const int w = text.empty() ? MPI_SUCCESS
                               : MPI_File_write_at(file, static_cast<MPI_Offset>(at), text.data(),
                                                   static_cast<int>(text.size()), MPI_CHAR, &status);
    if (rc == MPI_SUCCESS) rc = w;
    at += text.size();
    text.clear();
  }
  if (rc == MPI_SUCCESS && at != offset + length) rc = MPI_ERR_OTHER;  // a line that formats differently twice
  const int c = MPI_File_close(&file);
  comm.count_collective();
  if (rc == MPI_SUCCESS) rc = c;
  if (rc != MPI_SUCCESS)
    error = std::make_exception_ptr(IoError("writing '" + path + "' failed: " + mpi_error_text(rc)));
  settle_or_remove(comm, error, path);
}

}  // namespace rondel
