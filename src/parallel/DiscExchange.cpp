#include "parallel/DiscExchange.hpp"

#include <algorithm>
#include <iostream>

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

namespace {

// The index of `rank` in the ascending partner list, or stops the job: a disc that has to go to a rank
// that is not a partner has jumped further than a cell since the last migration, which the step's checks
// exclude, so this is a bug; the other ranks are already waiting for this rank's messages, so the only way
// out that never hangs is MPI_Abort.
std::size_t partner_index(const std::vector<int>& partners, int rank, const Communicator& comm, std::int64_t gid) {
  const auto it = std::lower_bound(partners.begin(), partners.end(), rank);
  if (it != partners.end() && *it == rank) return static_cast<std::size_t>(it - partners.begin());
  std::cerr << "rondel: internal error on rank " << comm.rank() << ": disc " << gid << " has to move to rank " << rank
            << ", which is not next to this rank's cells\n";
  MPI_Abort(comm.comm(), 4);
  return 0;
}

}  // namespace

DiscExchange::Counts DiscExchange::migrate(DiscStore& discs, ContactTable& pairs, ContactTable& wall_rows,
                                           const Decomposition& dec, const Communicator& comm, bool any_rank,
                                           ContactTable* bonds) {
  discs.truncate_to_owned();
  Counts counts;
  if (comm.size() == 1) return counts;
  const auto pair_index = rows_by_gid(pairs, true);
  const auto wall_index = rows_by_gid(wall_rows, false);
  const auto bond_index = bonds ? rows_by_gid(*bonds, true) : decltype(pair_index){};
  const std::vector<int>& to = dec.send_to();
  std::vector<ByteBuffer> out(any_rank ? static_cast<std::size_t>(comm.size()) : to.size());
  std::vector<bool> leaving(discs.n_owned(), false);
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    const int dest = dec.owner(discs.position[i]);
    if (dest == comm.rank()) continue;
    leaving[i] = true;
    ++counts.sent;
    ByteBuffer& b = out[any_rank ? static_cast<std::size_t>(dest) : partner_index(to, dest, comm, discs.gid[i])];
    pack_disc(discs, i, kMigrate, b);
    pack_rows_of(discs.gid[i], pair_index, pairs, b);
    pack_rows_of(discs.gid[i], wall_index, wall_rows, b);
    if (bonds) pack_rows_of(discs.gid[i], bond_index, *bonds, b);
  }
  const auto in = any_rank ? comm.all_to_all(out) : comm.exchange(to, out, dec.receive_from());
  discs.remove_owned(leaving);
  for (const ByteBuffer& b : in) {
    ByteReader r(b.bytes.data(), b.bytes.size());
    while (!r.done()) {
      append_disc(discs, kMigrate, r);
      ++counts.received;
      for (ContactTable* t : {&pairs, &wall_rows, bonds}) {
        if (!t) continue;
        const auto n = r.get<std::uint32_t>();
        for (std::uint32_t k = 0; k < n; ++k) unpack_row(*t, r);
      }
    }
  }
  discs.set_owned_count(discs.size());
  pairs.sort_unique_by_key();
  wall_rows.sort_unique_by_key();
  if (bonds) bonds->sort_unique_by_key();
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
  // Each owned disc goes to every neighbouring rank that owns one of the cells around its cell; every
  // neighbour gets a message (maybe empty), so each side knows what to expect without a collective.
  const std::vector<int>& partners = dec.neighbours();
  std::vector<std::vector<std::size_t>> lists(partners.size());
  std::vector<int> to;
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    dec.ghost_ranks(discs.position[i], to);
    for (int r : to) lists[partner_index(partners, r, comm, discs.gid[i])].push_back(i);
  }
  std::vector<ByteBuffer> out(partners.size());
  for (std::size_t k = 0; k < partners.size(); ++k) {
    for (std::size_t i : lists[k]) pack_disc(discs, i, kGhostCreate, out[k]);
    if (!lists[k].empty()) {
      send_ranks_.push_back(partners[k]);
      send_index_.push_back(std::move(lists[k]));
    }
  }
  const auto in = comm.exchange(partners, out, partners);
  const std::size_t create = record_bytes(discs, kGhostCreate), step = record_bytes(discs, kGhostStep);
  for (std::size_t k = 0; k < partners.size(); ++k) {
    const ByteBuffer& b = in[k];
    if (b.bytes.empty()) continue;
    ByteReader reader(b.bytes.data(), b.bytes.size());
    const std::size_t n = b.bytes.size() / create;
    for (std::size_t m = 0; m < n; ++m) append_disc(discs, kGhostCreate, reader);
    recv_ranks_.push_back(partners[k]);
    recv_bytes_.push_back(n * step);
    ghosts_ += n;
  }
}

void DiscExchange::update_ghosts(DiscStore& discs, const Communicator& comm) {
  if (comm.size() == 1) return;
  if (out_.size() != send_ranks_.size()) out_.resize(send_ranks_.size());
  for (std::size_t k = 0; k < send_ranks_.size(); ++k) {
    out_[k].bytes.clear();
    for (std::size_t i : send_index_[k]) pack_disc(discs, i, kGhostStep, out_[k]);
  }
  const auto in = comm.exchange(send_ranks_, out_, recv_ranks_, recv_bytes_);
  std::size_t g = first_ghost_;
  for (const ByteBuffer& b : in) {
    ByteReader reader(b.bytes.data(), b.bytes.size());
    while (!reader.done()) read_disc(discs, g++, kGhostStep, reader);
  }
}

std::size_t DiscExchange::memory_bytes() const {
  std::size_t n =
      (send_ranks_.capacity() + recv_ranks_.capacity()) * sizeof(int) + recv_bytes_.capacity() * sizeof(std::size_t);
  for (const auto& l : send_index_) n += l.capacity() * sizeof(std::size_t);
  for (const auto& b : out_) n += b.bytes.capacity();
  return n;
}

}  // namespace rondel
