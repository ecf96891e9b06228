#include "parallel/TextBlocks.hpp"

#include <mpi.h>

#include <algorithm>
#include <vector>

#include "core/Errors.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/CanonicalOrder.hpp"

namespace rondel {

namespace {

// This rank's bytes [S r/P, S (r+1)/P) of the file, in independent reads of at most 1 GiB: each rank opens the file
// alone (its blocks are contiguous, so collective buffering would gain nothing, and a rank need not wait for another).
std::string read_bytes(const std::string& path, const std::string& what, const Communicator& comm) {
  std::string bytes;
  agree(comm, [&] {
    MPI_File file = MPI_FILE_NULL;
    const int opened = MPI_File_open(MPI_COMM_SELF, path.c_str(), MPI_MODE_RDONLY, MPI_INFO_NULL, &file);
    if (opened != MPI_SUCCESS)
      throw InputError(what + " '" + path + "' cannot be read (" + mpi_error_text(opened) + ")");
    MPI_Offset size = 0;
    int code = MPI_File_get_size(file, &size);
    const auto S = static_cast<std::uint64_t>(size);
    const std::uint64_t begin = block_begin(S, comm.rank(), comm.size());
    const std::uint64_t end = block_begin(S, comm.rank() + 1, comm.size());
    if (code == MPI_SUCCESS) bytes.resize(end - begin);
    constexpr std::uint64_t kPiece = std::uint64_t{1} << 30;
    for (std::uint64_t at = 0; at < bytes.size() && code == MPI_SUCCESS; at += kPiece) {
      MPI_Status status;
      const int n = static_cast<int>(std::min<std::uint64_t>(kPiece, bytes.size() - at));
      code = MPI_File_read_at(file, static_cast<MPI_Offset>(begin + at), bytes.data() + at, n, MPI_CHAR, &status);
      int got = 0;
      if (code == MPI_SUCCESS) MPI_Get_count(&status, MPI_CHAR, &got);
      if (code == MPI_SUCCESS && got != n) code = MPI_ERR_TRUNCATE;  // the file shrank while it was read
    }
    MPI_File_close(&file);
    if (code != MPI_SUCCESS) throw InputError(what + " '" + path + "' cannot be read (" + mpi_error_text(code) + ")");
  });
  return bytes;
}

}  // namespace

std::string read_line_blocks(const std::string& path, const std::string& what, const Communicator& comm) {
  std::string text = read_bytes(path, what, comm);
  const int P = comm.size(), r = comm.rank();
  if (P == 1) return text;
  // The head of each block: up to and with its first '\n', or all of it. It belongs to the line that started in
  // the nearest block before with a '\n' (or rank 0's).
  const std::size_t nl = text.find('\n');
  const bool has_newline = nl != std::string::npos;
  const std::size_t head = r == 0 ? 0 : has_newline ? nl + 1 : text.size();
  ByteBuffer mine;
  mine.put(static_cast<std::uint8_t>(has_newline || r == 0));
  const std::vector<ByteBuffer> all = comm.all_gather(mine);
  std::vector<bool> keeps(static_cast<std::size_t>(P));
  for (int q = 0; q < P; ++q) keeps[q] = ByteReader(all[q].bytes.data(), all[q].bytes.size()).get<std::uint8_t>() != 0;
  std::vector<int> to, from;
  std::vector<ByteBuffer> out;
  if (r > 0) {
    int q = r - 1;
    while (!keeps[q]) --q;
    to.push_back(q);
    out.emplace_back();
    out.back().bytes.assign(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(head));
  }
  if (keeps[r])  // the heads of the blocks after, up to the first that ends a line
    for (int q = r + 1; q < P; ++q) {
      from.push_back(q);
      if (keeps[q]) break;
    }
  const std::vector<ByteBuffer> in = comm.exchange(to, out, from);
  text.erase(0, head);
  if (!keeps[r]) text.clear();
  for (const ByteBuffer& b : in) text.append(b.bytes.data(), b.bytes.size());
  return text;
}

std::int64_t first_line_number(std::int64_t lines, const Communicator& comm) {
  return static_cast<std::int64_t>(comm.exclusive_sum(static_cast<std::uint64_t>(lines))) + 1;
}

}  // namespace rondel
