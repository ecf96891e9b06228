#include "parallel/DiscExchange.hpp"

#include <algorithm>
#include <set>

#include "parallel/RecordPacking.hpp"

namespace rondel {

namespace {

// Rows (with state) per disc gid: (gid, row) sorted, for the rows that travel with a disc.
std::vector<std::pair<std::int64_t, std::size_t>> rows_by_gid(const ContactTable& t, bool both_ends) {
  std::vector<std::pair<std::int64_t, std::size_t>> out;
  for (std::size_t r = 0; r < t.size(); ++r) {
    if (!t.has_state(r)) continue;
    out.emplace_back(t.key[r].lo, r);
    if (both_ends) out.emplace_back(t.key[r].hi, r);
  }
  std::sort(out.begin(), out.end());
  return out;
}

void pack_rows_of(std::int64_t gid, const std::vector<std::pair<std::int64_t, std::size_t>>& index,
                  const ContactTable& t, ByteBuffer& out) {
  auto lo = std::lower_bound(index.begin(), index.end(), std::make_pair(gid, std::size_t{0}));
  auto hi = lo;
  while (hi != index.end() && hi->first == gid) ++hi;
  out.put(static_cast<std::uint32_t>(hi - lo));
  for (auto it = lo; it != hi; ++it) pack_row(t, it->second, out);
}

}  // namespace

DiscExchange::Counts DiscExchange::migrate(DiscStore& discs, ContactTable& pairs, ContactTable& wall_rows,
                                           const Decomposition& dec, const Communicator& comm) {
  discs.truncate_to_owned();
  Counts counts;
  const auto pair_index = rows_by_gid(pairs, true);
  const auto wall_index = rows_by_gid(wall_rows, false);
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.size()));
  std::vector<bool> leaving(discs.n_owned(), false);
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    const int dest = dec.owner(discs.position[i]);
    if (dest == comm.rank()) continue;
    leaving[i] = true;
    ++counts.sent;
    ByteBuffer& b = out[dest];
    pack_disc(discs, i, kMigrate, b);
    pack_rows_of(discs.gid[i], pair_index, pairs, b);
    pack_rows_of(discs.gid[i], wall_index, wall_rows, b);
  }
  if (comm.size() == 1) return counts;
  const auto in = comm.all_to_all(out);
  discs.remove_owned(leaving);
  for (const ByteBuffer& b : in) {
    ByteReader r(b.bytes.data(), b.bytes.size());
    while (!r.done()) {
      append_disc(discs, kMigrate, r);
      ++counts.received;
      for (ContactTable* t : {&pairs, &wall_rows}) {
        const auto n = r.get<std::uint32_t>();
        for (std::uint32_t k = 0; k < n; ++k) unpack_row(*t, r);
      }
    }
  }
  discs.set_owned_count(discs.size());
  pairs.sort_unique_by_key();
  wall_rows.sort_unique_by_key();
  return counts;
}

void DiscExchange::build_ghosts(DiscStore& discs, const Decomposition& dec, const Communicator& comm) {
  discs.truncate_to_owned();
  send_ranks_.clear();
  recv_ranks_.clear();
  send_index_.clear();
  recv_bytes_.clear();
  first_ghost_ = discs.n_owned();
  ghosts_ = 0;
  if (comm.size() == 1) return;
  std::vector<std::vector<std::size_t>> lists(static_cast<std::size_t>(comm.size()));
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    std::set<int> to;
    for (std::size_t c : dec.grid().stencil(dec.grid().cell_of(discs.position[i]))) to.insert(dec.owner_of_cell(c));
    to.erase(comm.rank());
    for (int r : to) lists[r].push_back(i);
  }
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.size()));
  for (int r = 0; r < comm.size(); ++r) {
    for (std::size_t i : lists[r]) pack_disc(discs, i, kGhostCreate, out[r]);
    if (!lists[r].empty()) {
      send_ranks_.push_back(r);
      send_index_.push_back(lists[r]);
    }
  }
  const auto in = comm.all_to_all(out);
  const std::size_t create = record_bytes(discs, kGhostCreate), step = record_bytes(discs, kGhostStep);
  for (int r = 0; r < comm.size(); ++r) {
    const ByteBuffer& b = in[r];
    if (b.bytes.empty()) continue;
    ByteReader reader(b.bytes.data(), b.bytes.size());
    const std::size_t n = b.bytes.size() / create;
    for (std::size_t k = 0; k < n; ++k) append_disc(discs, kGhostCreate, reader);
    recv_ranks_.push_back(r);
    recv_bytes_.push_back(n * step);
    ghosts_ += n;
  }
}

void DiscExchange::update_ghosts(DiscStore& discs, const Communicator& comm) const {
  if (comm.size() == 1) return;
  std::vector<ByteBuffer> out(send_ranks_.size());
  for (std::size_t k = 0; k < send_ranks_.size(); ++k) {
    out[k].bytes.reserve(send_index_[k].size() * 40);
    for (std::size_t i : send_index_[k]) pack_disc(discs, i, kGhostStep, out[k]);
  }
  const auto in = comm.exchange(send_ranks_, out, recv_ranks_, recv_bytes_);
  std::size_t g = first_ghost_;
  for (const ByteBuffer& b : in) {
    ByteReader reader(b.bytes.data(), b.bytes.size());
    while (!reader.done()) read_disc(discs, g++, kGhostStep, reader);
  }
}

}  // namespace rondel
