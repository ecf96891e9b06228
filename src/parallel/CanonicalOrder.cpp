#include "parallel/CanonicalOrder.hpp"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "parallel/Agreement.hpp"

namespace rondel {

namespace {

// Messages of at most 1 GiB: MPI counts are int.
constexpr std::uint64_t kChunk = std::uint64_t{1} << 30;
constexpr int kTag = 0x4f52;  // "OR"
// Regular samples per rank: O(P) samples in all, whatever the rank count.
constexpr int kSamples = 64;

bool key_less(const std::pair<OrderKey, std::uint64_t>& x, const std::pair<OrderKey, std::uint64_t>& y) {
  return x.first < y.first;
}

}  // namespace

void ByteExchange::run(const char* send, const std::vector<std::uint64_t>& send_bytes, std::vector<char>& recv,
                       std::vector<std::uint64_t>& recv_bytes, const Communicator& comm) {
  const int ranks = comm.size(), me = comm.rank();
  recv_bytes.resize(static_cast<std::size_t>(ranks));
  MPI_Alltoall(send_bytes.data(), 1, MPI_UINT64_T, recv_bytes.data(), 1, MPI_UINT64_T, comm.comm());
  std::uint64_t total = 0;
  for (const std::uint64_t b : recv_bytes) total += b;
  agree(comm, [&] { resize_buffer(recv, total); });
  requests_.clear();
  std::uint64_t in = 0, out = 0;
  for (int r = 0; r < ranks; ++r) {
    if (r == me) {
      std::copy(send + out, send + out + send_bytes[r], recv.data() + in);
    } else {
      for (std::uint64_t at = 0; at < recv_bytes[r]; at += kChunk)
        MPI_Irecv(recv.data() + in + at, static_cast<int>(std::min(kChunk, recv_bytes[r] - at)), MPI_BYTE, r, kTag,
                  comm.comm(), &requests_.emplace_back());
      for (std::uint64_t at = 0; at < send_bytes[r]; at += kChunk)
        MPI_Isend(send + out + at, static_cast<int>(std::min(kChunk, send_bytes[r] - at)), MPI_BYTE, r, kTag,
                  comm.comm(), &requests_.emplace_back());
    }
    in += recv_bytes[r];
    out += send_bytes[r];
  }
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
}

void CanonicalOrder::prepare(const Communicator& comm) {
  bytes_ = sizeof(OrderKey);
  const int ranks = comm.size(), me = comm.rank();
  agree(comm, [&] {
    if (!std::is_sorted(order_.begin(), order_.end(), key_less)) std::sort(order_.begin(), order_.end(), key_less);
    const auto twin = std::adjacent_find(order_.begin(), order_.end(),
                                         [](const Entry& x, const Entry& y) { return x.first == y.first; });
    if (twin != order_.end())
      throw std::runtime_error("CanonicalOrder: the key (" + std::to_string(twin->first.a) + ", " +
                               std::to_string(twin->first.b) + ") occurs twice on rank " + std::to_string(me));
  });
  ranges_.assign(static_cast<std::size_t>(ranks) + 1, 0);
  ranges_[ranks] = order_.size();
  send_bytes_.assign(static_cast<std::size_t>(ranks), 0);
  if (ranks == 1) return;
  choose_splitters(comm);
  // Rank r's range is [splitters_[r - 1], splitters_[r]): the first and last are open.
  for (int r = 1; r < ranks; ++r)
    ranges_[r] = static_cast<std::size_t>(
        std::lower_bound(order_.begin(), order_.end(), Entry{splitters_[r - 1], 0}, key_less) - order_.begin());
  std::uint64_t sent = 0;
  for (int r = 0; r < ranks; ++r)
    if (r != me) sent += ranges_[r + 1] - ranges_[r];
  agree(comm, [&] { resize_buffer(sent_, sent); });
  size_exchange(sizeof(OrderKey), comm);
}

void CanonicalOrder::size_exchange(std::size_t bytes, const Communicator& comm) {
  bytes_ = bytes;
  const int ranks = comm.size(), me = comm.rank();
  if (ranks == 1) return;
  send_bytes_.assign(static_cast<std::size_t>(ranks), 0);
  for (int r = 0; r < ranks; ++r)
    if (r != me) send_bytes_[r] = (ranges_[r + 1] - ranges_[r]) * bytes;
  agree(comm, [&] { resize_buffer(send_, sent_.size() * bytes); });
}

void CanonicalOrder::release() {
  rondel::release(order_, runs_, samples_, all_samples_, splitters_, ranges_, sent_, send_bytes_, recv_bytes_, send_,
                  recv_);
  exchange_ = ByteExchange();
  total_ = offset_ = 0;
}

void CanonicalOrder::choose_splitters(const Communicator& comm) {
  const int ranks = comm.size();
  const std::uint64_t n = order_.size();
  // Sample j stands for the records [j n / s, (j + 1) n / s) of this rank and is the first of them.
  samples_.resize(kSamples);
  for (std::uint64_t j = 0; j < kSamples; ++j) {
    const std::uint64_t lo = j * n / kSamples, hi = (j + 1) * n / kSamples;
    samples_[j] = {hi > lo ? order_[lo].first : OrderKey{}, hi - lo};
  }
  // The samples meet on rank 0 (kSamples P of them), which broadcasts the P - 1 splitters.
  constexpr int kBytes = kSamples * static_cast<int>(sizeof(Sample));
  if (comm.root()) all_samples_.resize(static_cast<std::size_t>(kSamples) * ranks);
  MPI_Gather(samples_.data(), kBytes, MPI_BYTE, all_samples_.data(), kBytes, MPI_BYTE, 0, comm.comm());
  splitters_.resize(static_cast<std::size_t>(ranks) - 1);
  if (comm.root()) {
    std::erase_if(all_samples_, [](const Sample& s) { return s.weight == 0; });
    std::sort(all_samples_.begin(), all_samples_.end(), [](const Sample& x, const Sample& y) { return x.key < y.key; });
    std::uint64_t total = 0;
    for (const Sample& s : all_samples_) total += s.weight;
    // A sample's key has about half a segment of every other rank below it besides the samples before it.
    const std::uint64_t bias = total / (2 * kSamples), whole = total / ranks, part = total % ranks;
    std::uint64_t before = 0;
    std::size_t m = 0;
    for (int r = 1; r < ranks; ++r) {
      const std::uint64_t target = whole * r + part * r / ranks;  // total r / P without overflow
      while (m < all_samples_.size() && before + bias < target) before += all_samples_[m++].weight;
      splitters_[r - 1] = m < all_samples_.size() ? all_samples_[m].key : OrderKey{INT64_MAX, INT64_MAX};
    }
  }
  MPI_Bcast(splitters_.data(), static_cast<int>(splitters_.size() * sizeof(OrderKey)), MPI_BYTE, 0, comm.comm());
}

void CanonicalOrder::finish(const Communicator& comm) {
  const int ranks = comm.size(), me = comm.rank();
  constexpr std::size_t record = sizeof(OrderKey);
  std::uint64_t received = 0;
  if (ranks > 1) {
    exchange_.run(send_.data(), send_bytes_, recv_, recv_bytes_, comm);
    for (const std::uint64_t b : recv_bytes_) received += b / record;
  }
  // The records kept here move to the front of order_, the received ones follow: sorted runs (the kept,
  // then one per sending rank), merged pairwise.
  agree(comm, [&] {
    const std::size_t kept = ranges_[me + 1] - ranges_[me];
    if (ranges_[me] > 0) std::copy(order_.begin() + ranges_[me], order_.begin() + ranges_[me + 1], order_.begin());
    resize_buffer(order_, kept + received);
    runs_.assign(1, 0);
    if (kept > 0) runs_.push_back(kept);
    std::uint64_t j = 0;
    for (int r = 0; r < ranks && ranks > 1; ++r) {
      for (const std::uint64_t end = j + recv_bytes_[r] / record; j < end; ++j) {
        std::memcpy(&order_[kept + j].first, recv_.data() + j * record, sizeof(OrderKey));
        order_[kept + j].second = j | kRemote;
      }
      if (kept + j > runs_.back()) runs_.push_back(kept + j);
    }
    merge_runs();
  });
  std::uint64_t count = order_.size();
  total_ = count, offset_ = 0;
  if (ranks == 1) return;
  MPI_Exscan(&count, &offset_, 1, MPI_UINT64_T, MPI_SUM, comm.comm());
  if (me == 0) offset_ = 0;  // MPI_Exscan leaves rank 0's result undefined
  MPI_Allreduce(&count, &total_, 1, MPI_UINT64_T, MPI_SUM, comm.comm());
}

void CanonicalOrder::merge_runs() {
  // Pairwise, in place: std::inplace_merge borrows a buffer of the shorter run at most (or merges without one), so
  // that the merge does not hold a second copy of this rank's keys.
  while (runs_.size() > 2) {
    std::size_t next = 1;
    for (std::size_t r = 0; r + 1 < runs_.size(); r += 2) {
      const std::size_t lo = runs_[r], mid = runs_[r + 1], hi = r + 2 < runs_.size() ? runs_[r + 2] : mid;
      std::inplace_merge(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi, key_less);
      runs_[next++] = hi;
    }
    runs_.resize(next);
  }
}

std::size_t CanonicalOrder::capacity_bytes() const {
  return order_.capacity() * sizeof(Entry) + runs_.capacity() * sizeof(std::size_t) +
         sent_.capacity() * sizeof(std::uint32_t) + (samples_.capacity() + all_samples_.capacity()) * sizeof(Sample) +
         splitters_.capacity() * sizeof(OrderKey) + ranges_.capacity() * sizeof(std::size_t) +
         (send_bytes_.capacity() + recv_bytes_.capacity()) * sizeof(std::uint64_t) + send_.capacity() +
         recv_.capacity() + exchange_.capacity_bytes();
}

}  // namespace rondel
