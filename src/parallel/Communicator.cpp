#include "parallel/Communicator.hpp"

#include <cstdlib>

namespace rondel {

MpiEnvironment::MpiEnvironment(int* argc, char*** argv) {
  int ready = 0;
  MPI_Initialized(&ready);
  // Open MPI's MPI-IO (OMPIO) opens a shared-file-pointer component with every file, and its "sm" component
  // keeps a POSIX semaphore named after the file in /dev/shm: a process killed inside MPI_File_open leaves
  // it behind, and every later open of a file of that name on the machine waits on it for good. Rondel uses
  // no shared file pointer, so that component is left out (unless the user set the parameter).
  if (!ready) setenv("OMPI_MCA_sharedfp", "^sm", 0);
  // And its MPI-IO implementation of choice is ROMIO where Open MPI has it (romio321 in Open MPI 4): on a
  // full disk OMPIO's collective writes report the failure on some ranks only (both HDF5 and Rondel then
  // wait in collectives that the others left) or on none (a checkpoint of holes taken for a good one);
  // ROMIO reports it on the rank that wrote. A priority only: where there is no ROMIO, OMPIO stays; a user's
  // own OMPI_MCA_io wins.
  if (!ready && !std::getenv("OMPI_MCA_io")) setenv("OMPI_MCA_io_romio321_priority", "100", 0);
  if (!ready) MPI_Init(argc, argv);
}

MpiEnvironment::~MpiEnvironment() {
  int done = 0;
  MPI_Finalized(&done);
  if (!done) MPI_Finalize();
}

Communicator::Communicator(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

double Communicator::max(double local) const {
  double out = local;
  ++stats_.collectives;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return out;
}

double Communicator::sum(double local) const {
  double out = local;
  ++stats_.collectives;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return out;
}

std::uint64_t Communicator::exclusive_sum(std::uint64_t local) const {
  if (size_ == 1) return 0;
  std::uint64_t below = 0;
  ++stats_.collectives;
  MPI_Exscan(&local, &below, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return rank_ == 0 ? 0 : below;  // MPI_Exscan leaves rank 0's result undefined
}

std::string mpi_error_text(int code) {
  char text[MPI_MAX_ERROR_STRING];
  int n = 0;
  MPI_Error_string(code, text, &n);
  return std::string(text, static_cast<std::size_t>(n));
}

std::int64_t Communicator::sum(std::int64_t local) const {
  std::int64_t out = local;
  ++stats_.collectives;
  MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_SUM, comm_);
  return out;
}

bool Communicator::any(bool local) const {
  int in = local ? 1 : 0, out = 0;
  ++stats_.collectives;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, comm_);
  return out != 0;
}

void Communicator::barrier() const { MPI_Barrier(comm_); }

}  // namespace rondel

namespace rondel {

std::int64_t Communicator::max(std::int64_t local) const {
  std::int64_t out = local;
  ++stats_.collectives;
  MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_MAX, comm_);
  return out;
}

void Communicator::exact_sum_in_place(ExactSum& local) const {
  local.normalise();
  ++stats_.collectives;
  MPI_Allreduce(MPI_IN_PLACE, local.limbs().data(), ExactSum::kLimbs, MPI_INT64_T, MPI_SUM, comm_);
  ++stats_.collectives;
  MPI_Allreduce(MPI_IN_PLACE, &local.nonfinite_count(), 1, MPI_INT64_T, MPI_SUM, comm_);
  local.normalise();
}

double Communicator::exact_sum(ExactSum local) const {
  exact_sum_in_place(local);
  return local.value();
}

std::vector<ByteBuffer> Communicator::all_to_all(const std::vector<ByteBuffer>& out) const {
  // 64-bit counts, then the data point to point (in 1 GiB pieces) with the ranks that send or receive any.
  std::vector<std::uint64_t> send_counts(static_cast<std::size_t>(size_)), recv_counts(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) send_counts[r] = out[r].bytes.size();
  ++stats_.collectives;
  MPI_Alltoall(send_counts.data(), 1, MPI_UINT64_T, recv_counts.data(), 1, MPI_UINT64_T, comm_);
  std::vector<int> to, from;
  std::vector<ByteBuffer> sends;
  std::vector<std::size_t> sizes;
  for (int r = 0; r < size_; ++r) {
    if (send_counts[r] > 0) to.push_back(r), sends.push_back(out[r]);
    if (recv_counts[r] > 0) from.push_back(r), sizes.push_back(recv_counts[r]);
  }
  auto received = exchange(to, sends, from, sizes);
  std::vector<ByteBuffer> in(static_cast<std::size_t>(size_));
  for (std::size_t k = 0; k < from.size(); ++k) in[from[k]] = std::move(received[k]);
  return in;
}

namespace {
// Messages are sent in pieces of at most 1 GiB, so that no MPI count overflows an int whatever the size.
constexpr std::size_t kPiece = std::size_t{1} << 30;
constexpr int kTag = 7, kSizeTag = 8;
}  // namespace

std::vector<ByteBuffer> Communicator::exchange(const std::vector<int>& to, const std::vector<ByteBuffer>& out,
                                               const std::vector<int>& from,
                                               const std::vector<std::size_t>& sizes) const {
  std::vector<ByteBuffer> in(from.size());
  std::vector<MPI_Request> requests;
  requests.reserve(to.size() + from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    in[k].bytes.resize(sizes[k]);
    for (std::size_t at = 0; at < sizes[k] || (at == 0 && sizes[k] == 0); at += kPiece) {
      requests.emplace_back();
      MPI_Irecv(in[k].bytes.data() + at, static_cast<int>(std::min(kPiece, sizes[k] - at)), MPI_BYTE, from[k], kTag,
                comm_, &requests.back());
      if (sizes[k] == 0) break;
    }
  }
  for (std::size_t k = 0; k < to.size(); ++k) {
    const std::size_t n = out[k].bytes.size();
    for (std::size_t at = 0; at < n || (at == 0 && n == 0); at += kPiece) {
      requests.emplace_back();
      MPI_Isend(out[k].bytes.data() + at, static_cast<int>(std::min(kPiece, n - at)), MPI_BYTE, to[k], kTag, comm_,
                &requests.back());
      ++stats_.messages;
      if (n == 0) break;
    }
    stats_.bytes += static_cast<std::int64_t>(n);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return in;
}

std::vector<ByteBuffer> Communicator::exchange(const std::vector<int>& to, const std::vector<ByteBuffer>& out,
                                               const std::vector<int>& from) const {
  std::vector<std::uint64_t> in_sizes(from.size()), out_sizes(to.size());
  std::vector<MPI_Request> requests;
  requests.reserve(to.size() + from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    requests.emplace_back();
    MPI_Irecv(&in_sizes[k], 1, MPI_UINT64_T, from[k], kSizeTag, comm_, &requests.back());
  }
  for (std::size_t k = 0; k < to.size(); ++k) {
    out_sizes[k] = out[k].bytes.size();
    requests.emplace_back();
    MPI_Isend(&out_sizes[k], 1, MPI_UINT64_T, to[k], kSizeTag, comm_, &requests.back());
    ++stats_.messages;
    stats_.bytes += static_cast<std::int64_t>(sizeof(std::uint64_t));
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return exchange(to, out, from, std::vector<std::size_t>(in_sizes.begin(), in_sizes.end()));
}

void Communicator::broadcast(std::vector<char>& bytes, int root) const {
  long long n = static_cast<long long>(bytes.size());
  ++stats_.collectives;
  MPI_Bcast(&n, 1, MPI_LONG_LONG, root, comm_);
  bytes.resize(static_cast<std::size_t>(n));
  ++stats_.collectives;
  MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, root, comm_);
}

std::vector<ByteBuffer> Communicator::gather(const ByteBuffer& mine, int root) const {
  int n = static_cast<int>(mine.bytes.size());
  std::vector<int> counts(size_), displs(size_);
  ++stats_.collectives;
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
  int total = 0;
  for (int r = 0; r < size_; ++r) displs[r] = total, total += (rank_ == root ? counts[r] : 0);
  std::vector<char> all(static_cast<std::size_t>(total));
  ++stats_.collectives;
  MPI_Gatherv(mine.bytes.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, root, comm_);
  std::vector<ByteBuffer> out;
  if (rank_ != root) return out;
  out.resize(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) out[r].bytes.assign(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
  return out;
}

std::vector<ByteBuffer> Communicator::all_gather(const ByteBuffer& mine) const {
  int n = static_cast<int>(mine.bytes.size());
  std::vector<int> counts(size_), displs(size_);
  ++stats_.collectives;
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  int total = 0;
  for (int r = 0; r < size_; ++r) displs[r] = total, total += counts[r];
  std::vector<char> all(static_cast<std::size_t>(total));
  ++stats_.collectives;
  MPI_Allgatherv(mine.bytes.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, comm_);
  std::vector<ByteBuffer> out(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) out[r].bytes.assign(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
  return out;
}

}  // namespace rondel
