#pragma once
#include <compare>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/Buffers.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// Rows [r total/P, (r+1) total/P) of a file's dataset are read by rank r.
inline std::uint64_t block_begin(std::uint64_t total, int rank, int ranks) {
  return total * static_cast<std::uint64_t>(rank) / static_cast<std::uint64_t>(ranks);
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
// them by local index. Every buffer is a member that keeps its capacity until release().
//
// The keys travel first (arrange_keys); the records' bytes then follow in as many exchanges as the caller likes
// (exchange: a checkpoint sends one dataset at a time, so that no rank holds whole records of every other rank).
// Memory per rank: 24 B per local or received record (key and index, sorted; up to half that again while merging), 4 B
// per record sent, 16 B of key or the bytes of one exchange per record sent or received, 16 B P of counts and
// splitters; rank 0 also holds the 24 B x 64 P samples. release() gives it all back. A
// splitter misses its quantile by at most N/(2 s) records (the samples' segments), so a rank's range holds
// at most N/P + N/64 records (the errors of the ranks' segments add up only when they all lean one way).
class CanonicalOrder {
 public:
  // Collective. This rank has `n` records; `key_of(i)` is the OrderKey of record i. Puts the keys in order: this
  // rank's range of the global order is known after it (count(), key(k), is_local(k), local_index(k)).
  template <class KeyOf>
  void arrange_keys(std::size_t n, KeyOf&& key_of, const Communicator& comm);
  // Collective, after arrange_keys: `pack(i, out)` writes `bytes` bytes of local record i to out for each record
  // that goes to another rank; received(k) then points to those bytes of a received record. May be repeated
  // with other bytes (each replaces the last).
  template <class Pack>
  void exchange(std::size_t bytes, Pack&& pack, const Communicator& comm);
  // Both at once: the keys, then `bytes` bytes of each record.
  template <class KeyOf, class Pack>
  void arrange(std::size_t n, KeyOf&& key_of, std::size_t bytes, Pack&& pack, const Communicator& comm) {
    arrange_keys(n, key_of, comm);
    exchange(bytes, pack, comm);
  }
  void arrange(const std::vector<OrderKey>& keys, std::size_t bytes, auto&& pack, const Communicator& comm) {
    arrange(
        keys.size(), [&keys](std::size_t i) { return keys[i]; }, bytes, pack, comm);
  }
  // Frees every buffer (a later arrange allocates anew).
  void release();

  // This rank's records are the global rows [offset(), offset() + count()) of total().
  std::uint64_t total() const { return total_; }
  std::uint64_t offset() const { return offset_; }
  std::uint64_t count() const { return order_.size(); }
  // The k-th record of this rank's range: a local record (its index) or a received one (its bytes).
  bool is_local(std::size_t k) const { return (order_[k].second & kRemote) == 0; }
  std::size_t local_index(std::size_t k) const { return static_cast<std::size_t>(order_[k].second); }
  const char* received(std::size_t k) const { return recv_.data() + (order_[k].second & ~kRemote) * bytes_; }
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
  void prepare(const Communicator& comm);
  void choose_splitters(const Communicator& comm);
  // Exchanges the packed keys, merges the kept and the received ones, computes offset and total.
  void finish(const Communicator& comm);
  // Sizes the buffers of an exchange of `bytes` bytes a record.
  void size_exchange(std::size_t bytes, const Communicator& comm);
  // Merges the sorted runs order_[runs_[k], runs_[k + 1]) into one (in place, log2(runs) passes).
  void merge_runs();

  std::size_t bytes_ = 0;
  std::uint64_t total_ = 0, offset_ = 0;
  std::vector<Entry> order_;  // sorted local keys; after finish() this rank's range, in order
  std::vector<std::size_t> runs_;
  std::vector<Sample> samples_, all_samples_;
  std::vector<OrderKey> splitters_;
  std::vector<std::size_t> ranges_;  // order_[ranges_[r], ranges_[r + 1]) went to rank r
  std::vector<std::uint32_t> sent_;  // the local records sent, in the order sent (rank by rank)
  std::vector<std::uint64_t> send_bytes_, recv_bytes_;
  std::vector<char> send_, recv_;
  ByteExchange exchange_;
};

template <class KeyOf>
void CanonicalOrder::arrange_keys(std::size_t n, KeyOf&& key_of, const Communicator& comm) {
  agree(comm, [&] {
    if (n >= UINT32_MAX) throw std::length_error("CanonicalOrder: 2^32 records or more on one rank");
    resize_buffer(order_, n);
    for (std::size_t i = 0; i < n; ++i) order_[i] = {key_of(i), i};
  });
  prepare(comm);
  std::size_t at = 0;
  for (int r = 0; r < comm.size(); ++r) {
    if (r == comm.rank()) continue;
    for (std::size_t k = ranges_[r]; k < ranges_[r + 1]; ++k, ++at) {
      std::memcpy(send_.data() + at * sizeof(OrderKey), &order_[k].first, sizeof(OrderKey));
      sent_[at] = static_cast<std::uint32_t>(order_[k].second);
    }
  }
  finish(comm);
}

template <class Pack>
void CanonicalOrder::exchange(std::size_t bytes, Pack&& pack, const Communicator& comm) {
  size_exchange(bytes, comm);
  if (comm.size() == 1) return;
  for (std::size_t s = 0; s < sent_.size(); ++s) pack(static_cast<std::size_t>(sent_[s]), send_.data() + s * bytes);
  exchange_.run(send_.data(), send_bytes_, recv_, recv_bytes_, comm);
}

}  // namespace rondel
