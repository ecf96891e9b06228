#include "parallel/Communicator.hpp"

namespace rondel {

MpiEnvironment::MpiEnvironment(int* argc, char*** argv) {
  int ready = 0;
  MPI_Initialized(&ready);
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
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return out;
}

double Communicator::sum(double local) const {
  double out = local;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return out;
}

std::int64_t Communicator::sum(std::int64_t local) const {
  std::int64_t out = local;
  MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_SUM, comm_);
  return out;
}

bool Communicator::any(bool local) const {
  int in = local ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, comm_);
  return out != 0;
}

void Communicator::barrier() const { MPI_Barrier(comm_); }

}  // namespace rondel

namespace rondel {

std::int64_t Communicator::max(std::int64_t local) const {
  std::int64_t out = local;
  MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_MAX, comm_);
  return out;
}

void Communicator::exact_sum_in_place(ExactSum& local) const {
  local.normalise();
  MPI_Allreduce(MPI_IN_PLACE, local.limbs().data(), ExactSum::kLimbs, MPI_INT64_T, MPI_SUM, comm_);
  MPI_Allreduce(MPI_IN_PLACE, &local.nonfinite_count(), 1, MPI_INT64_T, MPI_SUM, comm_);
  local.normalise();
}

double Communicator::exact_sum(ExactSum local) const {
  exact_sum_in_place(local);
  return local.value();
}

std::vector<ByteBuffer> Communicator::all_to_all(const std::vector<ByteBuffer>& out) const {
  std::vector<int> send_counts(size_), recv_counts(size_), send_displs(size_), recv_displs(size_);
  for (int r = 0; r < size_; ++r) send_counts[r] = static_cast<int>(out[r].bytes.size());
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_);
  std::vector<char> send, recv;
  for (int r = 0; r < size_; ++r) {
    send_displs[r] = static_cast<int>(send.size());
    send.insert(send.end(), out[r].bytes.begin(), out[r].bytes.end());
  }
  int total = 0;
  for (int r = 0; r < size_; ++r) recv_displs[r] = total, total += recv_counts[r];
  recv.resize(static_cast<std::size_t>(total));
  MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), MPI_BYTE, recv.data(), recv_counts.data(),
                recv_displs.data(), MPI_BYTE, comm_);
  std::vector<ByteBuffer> in(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r)
    in[r].bytes.assign(recv.begin() + recv_displs[r], recv.begin() + recv_displs[r] + recv_counts[r]);
  return in;
}

std::vector<ByteBuffer> Communicator::exchange(const std::vector<int>& to, const std::vector<ByteBuffer>& out,
                                               const std::vector<int>& from,
                                               const std::vector<std::size_t>& sizes) const {
  std::vector<ByteBuffer> in(from.size());
  std::vector<MPI_Request> requests;
  requests.reserve(to.size() + from.size());
  for (std::size_t k = 0; k < from.size(); ++k) {
    in[k].bytes.resize(sizes[k]);
    requests.emplace_back();
    MPI_Irecv(in[k].bytes.data(), static_cast<int>(sizes[k]), MPI_BYTE, from[k], 7, comm_, &requests.back());
  }
  for (std::size_t k = 0; k < to.size(); ++k) {
    requests.emplace_back();
    MPI_Isend(out[k].bytes.data(), static_cast<int>(out[k].bytes.size()), MPI_BYTE, to[k], 7, comm_, &requests.back());
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  return in;
}

void Communicator::broadcast(std::vector<char>& bytes, int root) const {
  long long n = static_cast<long long>(bytes.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, root, comm_);
  bytes.resize(static_cast<std::size_t>(n));
  MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_BYTE, root, comm_);
}

std::vector<ByteBuffer> Communicator::gather(const ByteBuffer& mine, int root) const {
  int n = static_cast<int>(mine.bytes.size());
  std::vector<int> counts(size_), displs(size_);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
  int total = 0;
  for (int r = 0; r < size_; ++r) displs[r] = total, total += (rank_ == root ? counts[r] : 0);
  std::vector<char> all(static_cast<std::size_t>(total));
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
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  int total = 0;
  for (int r = 0; r < size_; ++r) displs[r] = total, total += counts[r];
  std::vector<char> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.bytes.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, comm_);
  std::vector<ByteBuffer> out(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) out[r].bytes.assign(all.begin() + displs[r], all.begin() + displs[r] + counts[r]);
  return out;
}

}  // namespace rondel
