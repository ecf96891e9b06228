#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Decomposition.hpp"

namespace rondel {

// Moves discs between ranks (docs/design.md section 6):
//  - migrate(): every owned disc goes to the owner of its cell, with every contact row that carries state
//    (history and last forces; a pair's row exists on both ranks of a border pair, so copies are identical);
//  - build_ghosts(): each owned disc is copied to every other rank owning one of the 8 cells around its
//    cell (periodic images included: a ghost is a bit copy, never a shifted one);
//  - update_ghosts(): refreshes the ghosts' position, velocity and omega every step between rebuilds,
//    point to point with the ranks of the ghost lists.
// All three talk only to the neighbouring ranks of the decomposition, point to point (64-bit sizes).
class DiscExchange {
 public:
  struct Counts {
    std::size_t sent = 0, received = 0;
  };

  // Drops ghosts, sends away owned discs whose cell belongs to another rank and appends those received.
  // The rows of `pairs` and `wall_rows` are extended with the received rows, sorted by key, de-duplicated;
  // their local indices are stale (they only serve as history for the next neighbour build).
  // The partners are dec.send_to() and dec.receive_from() (point to point); `any_rank` (set-up only: discs
  // read by file block) sends to any rank with one all-to-all instead. `bonds` (a scene with bonds): its rows
  // travel too (both ends, as the pairs'); the rows left behind are dropped by bonds::relink after the ghosts.
  Counts migrate(DiscStore& discs, ContactTable& pairs, ContactTable& wall_rows, const Decomposition& dec,
                 const Communicator& comm, bool any_rank = false, ContactTable* bonds = nullptr);
  void build_ghosts(DiscStore& discs, const Decomposition& dec, const Communicator& comm);
  void update_ghosts(DiscStore& discs, const Communicator& comm);
  std::size_t ghost_count() const { return ghosts_; }
  // Room for the ghosts of n owned discs in a compact region (about 7.8 sqrt(n) measured, docs/scaling.md; twice
  // that), reserved with the discs so that the first ghosts do not copy every field of the store to a new one.
  static std::size_t ghost_room(std::size_t n) {
    return static_cast<std::size_t>(16.0 * std::sqrt(static_cast<double>(n))) + 1024;
  }
  // Bytes this rank holds for the exchanges (ghost lists and the reused send buffers).
  std::size_t memory_bytes() const;

 private:
  std::vector<int> send_ranks_, recv_ranks_;
  std::vector<std::vector<std::size_t>> send_index_;
  std::vector<std::size_t> recv_bytes_;
  std::vector<ByteBuffer> out_;  // the ghost update's send buffers, reused every step
  std::size_t ghosts_ = 0;
  std::size_t first_ghost_ = 0;
};

}  // namespace rondel
