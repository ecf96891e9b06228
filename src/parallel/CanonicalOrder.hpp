#pragma once
#include <compare>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "parallel/Agreement.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// Rows [r total/P, (r+1) total/P) of a file's dataset are read by rank r.
inline std::uint64_t block_begin(std::uint64_t total, int rank, int ranks) {
  return total * static_cast<std::uint64_t>(rank) / static_cast<std::uint64_t>(ranks);
}

// Resizes a reused buffer: when it must grow, to n and 1/16 more (not the doubling of push_back and
// resize), so that its capacity stays near what one checkpoint needs and later ones fit.
template <class T>
void resize_buffer(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(n + n / 16);
  v.resize(n);
}

// A record's place in the file order: discs by (gid, 0), contact rows by (lo, hi) (a wall row: (gid, wall)).
struct OrderKey {
  std::int64_t a = 0, b = 0;
  friend auto operator<=>(const OrderKey&, const OrderKey&) = default;
};

// Sends bytes to every rank and receives from every rank, point to point with the ranks that have something
// to send (counts exchanged first), in messages of at most 1 GiB: 64-bit sizes throughout. `send` holds the
// bytes for rank 0, then rank 1, ... (`send_bytes[r]` each); `recv` gets those from rank 0, 1, ... in order,
// `recv_bytes[r]` each. Collective over `comm`. The vectors are resized, never shrunk (reused buffers).
class ByteExchange {
 public:
  void run(const char* send, const std::vector<std::uint64_t>& send_bytes, std::vector<char>& recv,
           std::vector<std::uint64_t>& recv_bytes, const Communicator& comm);
  std::size_t capacity_bytes() const { return requests_.capacity() * sizeof(MPI_Request); }

 private:
  std::vector<MPI_Request> requests_;
};

// The global ascending key order of records spread over the ranks, without a list of keys on any rank (a
// distributed sample sort): each rank sorts its keys; s = 64 regular samples per rank, each weighted by the
// records it stands for, are gathered on rank 0 (64 P samples: O(P)), which picks P - 1 splitters at the
// weighted quantiles and broadcasts them; the records of each key range go to its rank (point to point), are
// merged there, and the prefix sum (MPI_Exscan) of the ranks' counts gives each rank its first global row.
// Keys must be unique over all ranks. Records that stay on their rank are never copied: the order refers to
// them by local index. Every buffer is a member that keeps its capacity, so an object kept across
// checkpoints allocates nothing after the first.
//
// Memory per rank: 24 B per local or received record (key and index, sorted; twice that while merging), 16 B + the
// record size per record sent or received, 16 B P of counts and splitters; rank 0 also holds the 24 B x 64 P samples. A
// splitter misses its quantile by at most N/(2 s) records (the samples' segments), so a rank's range holds
// at most N/P + N/64 records (the errors of the ranks' segments add up only when they all lean one way).
class CanonicalOrder {
 public:
  // Collective. This rank has `n` records; `key_of(i)` is the OrderKey of record i, `pack(i, out)` writes
  // its `bytes` bytes to out (only for records that go to another rank).
  template <class KeyOf, class Pack>
  void arrange(std::size_t n, KeyOf&& key_of, std::size_t bytes, Pack&& pack, const Communicator& comm);
  void arrange(const std::vector<OrderKey>& keys, std::size_t bytes, auto&& pack, const Communicator& comm) {
    arrange(
        keys.size(), [&keys](std::size_t i) { return keys[i]; }, bytes, pack, comm);
  }

  // This rank's records are the global rows [offset(), offset() + count()) of total().
  std::uint64_t total() const { return total_; }
  std::uint64_t offset() const { return offset_; }
  std::uint64_t count() const { return order_.size(); }
  // The k-th record of this rank's range: a local record (its index) or a received one (its bytes).
  bool is_local(std::size_t k) const { return (order_[k].second & kRemote) == 0; }
  std::size_t local_index(std::size_t k) const { return static_cast<std::size_t>(order_[k].second); }
  const char* received(std::size_t k) const {
    return recv_.data() + (order_[k].second & ~kRemote) * (sizeof(OrderKey) + bytes_) + sizeof(OrderKey);
  }
  const OrderKey& key(std::size_t k) const { return order_[k].first; }

  // Bytes held by the buffers now (their capacity): the peak of the last arrange() and all before.
  std::size_t capacity_bytes() const;

 private:
  static constexpr std::uint64_t kRemote = std::uint64_t{1} << 63;
  using Entry = std::pair<OrderKey, std::uint64_t>;
  struct Sample {
    OrderKey key;
    std::uint64_t weight;
  };

  // Sorts the local keys (in order_), chooses the splitters, sizes the send buffer (ranges_ per rank).
  void prepare(std::size_t bytes, const Communicator& comm);
  void choose_splitters(const Communicator& comm);
  // Exchanges the packed records, merges the kept and the received ones, computes offset and total.
  void finish(const Communicator& comm);
  // Merges the sorted runs order_[runs_[k], runs_[k + 1]) into one (through spare_, log2(runs) passes).
  void merge_runs();

  std::size_t bytes_ = 0;
  std::uint64_t total_ = 0, offset_ = 0;
  std::vector<Entry> order_;  // sorted local keys; after finish() this rank's range, in order
  std::vector<Entry> spare_;  // the other half of the merge passes
  std::vector<std::size_t> runs_;
  std::vector<Sample> samples_, all_samples_;
  std::vector<OrderKey> splitters_;
  std::vector<std::size_t> ranges_;  // order_[ranges_[r], ranges_[r + 1]) goes to rank r
  std::vector<std::uint64_t> send_bytes_, recv_bytes_;
  std::vector<char> send_, recv_;
  ByteExchange exchange_;
};

template <class KeyOf, class Pack>
void CanonicalOrder::arrange(std::size_t n, KeyOf&& key_of, std::size_t bytes, Pack&& pack, const Communicator& comm) {
  agree(comm, [&] {
    resize_buffer(order_, n);
    for (std::size_t i = 0; i < n; ++i) order_[i] = {key_of(i), i};
  });
  prepare(bytes, comm);
  const std::size_t record = sizeof(OrderKey) + bytes;
  std::size_t at = 0;
  for (int r = 0; r < comm.size(); ++r) {
    if (r == comm.rank()) continue;
    for (std::size_t k = ranges_[r]; k < ranges_[r + 1]; ++k, at += record) {
      std::memcpy(send_.data() + at, &order_[k].first, sizeof(OrderKey));
      pack(static_cast<std::size_t>(order_[k].second), send_.data() + at + sizeof(OrderKey));
    }
  }
  finish(comm);
}

}  // namespace rondel
