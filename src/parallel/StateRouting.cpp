// The distributed gid directory and the routing of file rows to their owners (StateFile.hpp): the restart's path,
// O(N/P + P) per rank.
#include <algorithm>
#include <cstring>
#include <limits>

#include "core/Errors.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/RecordPacking.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {

namespace {

void note_bytes(std::size_t bytes) { note_checkpoint_structure_bytes(bytes); }

}  // namespace

namespace {

// Packs `items` records of `bytes` bytes into `send` grouped by destination rank (dest(item) < 0: left out),
// with the bytes per rank in `send_bytes`: the layout ByteExchange sends.
template <class Dest, class Pack>
void pack_by_rank(std::size_t items, std::size_t bytes, int ranks, Dest&& dest, Pack&& pack, std::vector<char>& send,
                  std::vector<std::uint64_t>& send_bytes) {
  std::vector<std::uint64_t> at(static_cast<std::size_t>(ranks) + 1, 0);
  for (std::size_t k = 0; k < items; ++k)
    if (const int d = dest(k); d >= 0) ++at[d + 1];
  send_bytes.resize(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r) send_bytes[r] = at[r + 1] * bytes, at[r + 1] += at[r];
  resize_buffer(send, at[ranks] * bytes);
  for (std::size_t k = 0; k < items; ++k)
    if (const int d = dest(k); d >= 0) pack(k, send.data() + (at[d]++) * bytes);
}

int home_rank(std::int64_t gid, int ranks) {
  const std::int64_t r = gid % ranks;
  return static_cast<int>(r < 0 ? r + ranks : r);
}

// The buffers of one routing: what is sent, what came, and the bytes per rank of each.
struct Routing {
  ByteExchange exchange;
  std::vector<char> send, recv;
  std::vector<std::uint64_t> send_bytes, recv_bytes;
};

// The directory part of this rank: (gid, owner rank) of every owned gid whose home rank this is, sorted.
std::vector<std::pair<std::int64_t, int>> gid_directory(const DiscStore& discs, Routing& x, const Communicator& comm) {
  const int ranks = comm.size();
  const std::int64_t* gid = discs.gid.data();
  agree(comm, [&] {
    pack_by_rank(
        discs.n_owned(), sizeof(std::int64_t), ranks, [&](std::size_t i) { return home_rank(gid[i], ranks); },
        [&](std::size_t i, char* out) { std::memcpy(out, gid + i, sizeof(std::int64_t)); }, x.send, x.send_bytes);
  });
  x.exchange.run(x.send.data(), x.send_bytes, x.recv, x.recv_bytes, comm);
  std::vector<std::pair<std::int64_t, int>> owner;
  agree(comm, [&] {
    owner.reserve(x.recv.size() / sizeof(std::int64_t));
    std::size_t at = 0;
    for (int r = 0; r < ranks; ++r)
      for (std::uint64_t k = 0; k < x.recv_bytes[r] / sizeof(std::int64_t); ++k, at += sizeof(std::int64_t)) {
        std::int64_t g = 0;
        std::memcpy(&g, x.recv.data() + at, sizeof g);
        owner.emplace_back(g, r);
      }
    std::sort(owner.begin(), owner.end());
  });
  return owner;
}

// The home rank's answers to the gids asked in x.recv: their owners (-1: no rank owns the disc), in the
// order asked, for ByteExchange back to the askers.
void answer_owners(const std::vector<std::pair<std::int64_t, int>>& owner, const Routing& x, int ranks,
                   std::vector<char>& answers, std::vector<std::uint64_t>& answer_bytes) {
  const std::size_t asked = x.recv.size() / sizeof(std::int64_t);
  resize_buffer(answers, asked * sizeof(std::int32_t));
  for (std::size_t j = 0; j < asked; ++j) {
    std::int64_t g = 0;
    std::memcpy(&g, x.recv.data() + j * sizeof g, sizeof g);
    const auto it = std::lower_bound(owner.begin(), owner.end(), std::make_pair(g, -1));
    const std::int32_t r = (it != owner.end() && it->first == g) ? it->second : -1;
    std::memcpy(answers.data() + j * sizeof r, &r, sizeof r);
  }
  answer_bytes.resize(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r) answer_bytes[r] = x.recv_bytes[r] / sizeof(std::int64_t) * sizeof(std::int32_t);
}

}  // namespace

void check_unique_gids(const DiscStore& discs, const std::string& path, const Communicator& comm) {
  // Each gid meets its copies on its home rank (the directory of route_rows_to_owners); the smallest gid
  // found twice is named, the same one on any rank count.
  Routing x;
  const std::vector<std::pair<std::int64_t, int>> owner = gid_directory(discs, x, comm);
  std::int64_t twice = std::numeric_limits<std::int64_t>::max();
  for (std::size_t k = 1; k < owner.size(); ++k)
    if (owner[k].first == owner[k - 1].first) {
      twice = owner[k].first;
      break;
    }
  // min over the ranks as minus the max of minus (the gids are >= 0 here: checked before)
  twice = -comm.max(-twice);
  if (twice != std::numeric_limits<std::int64_t>::max())
    throw InputError("'" + path + "': disc id " + std::to_string(twice) +
                     " occurs more than once in /discs/gid; every disc has an id of its own (a file "
                     "written by another program? Rondel's writers never repeat an id)");
}

void route_rows_to_owners(ContactTable& rows, bool both_ends, const DiscStore& discs, const Communicator& comm) {
  const int ranks = comm.size();
  // 1. The directory: each owned gid registered on its home rank, as (gid, owner).
  Routing x;
  const std::vector<std::pair<std::int64_t, int>> owner = gid_directory(discs, x, comm);
  // 2. The owner of each end of each row (item k: row k / ends, end k % ends), asked of its home rank.
  const std::size_t ends = both_ends ? 2 : 1, items = rows.size() * ends;
  auto gid_of = [&](std::size_t k) { return k % ends ? rows.key[k / ends].hi : rows.key[k / ends].lo; };
  agree(comm, [&] {
    pack_by_rank(
        items, sizeof(std::int64_t), ranks, [&](std::size_t k) { return home_rank(gid_of(k), ranks); },
        [&](std::size_t k, char* out) {
          const std::int64_t g = gid_of(k);
          std::memcpy(out, &g, sizeof g);
        },
        x.send, x.send_bytes);
  });
  x.exchange.run(x.send.data(), x.send_bytes, x.recv, x.recv_bytes, comm);
  std::vector<char> answers;
  std::vector<std::uint64_t> answer_bytes, reply_bytes;
  agree(comm, [&] { answer_owners(owner, x, ranks, answers, answer_bytes); });
  std::vector<char> replies;
  x.exchange.run(answers.data(), answer_bytes, replies, reply_bytes, comm);
  // The replies of rank d answer the items sent to d, in ascending item order (pack_by_rank's layout).
  std::vector<std::int32_t> end_owner;
  agree(comm, [&] {
    std::vector<std::uint64_t> at(static_cast<std::size_t>(ranks) + 1, 0);
    for (int r = 0; r < ranks; ++r) at[r + 1] = at[r] + reply_bytes[r] / sizeof(std::int32_t);
    end_owner.resize(items);
    for (std::size_t k = 0; k < items; ++k)
      std::memcpy(&end_owner[k], replies.data() + (at[home_rank(gid_of(k), ranks)]++) * sizeof(std::int32_t),
                  sizeof(std::int32_t));
  });
  note_bytes(x.send.capacity() + x.recv.capacity() + owner.capacity() * sizeof(owner[0]) + answers.capacity() +
             replies.capacity() + end_owner.capacity() * sizeof(std::int32_t));
  // Each buffer is freed as soon as it is used up (a restart's rows are the largest thing a rank reads).
  release(answers, replies, x.recv);
  // 3. Each row to the owner of each end (once when both ends have the same owner; none: dropped).
  const std::size_t bytes = row_bytes(rows);
  agree(comm, [&] {
    pack_by_rank(
        items, bytes, ranks,
        [&](std::size_t k) { return (k % ends && end_owner[k] == end_owner[k - 1]) ? -1 : end_owner[k]; },
        [&](std::size_t k, char* out) { pack_row_bytes(rows, k / ends, out); }, x.send, x.send_bytes);
  });
  release(end_owner);
  rows = rows.empty_like();  // the rows are in x.send now
  x.exchange.run(x.send.data(), x.send_bytes, x.recv, x.recv_bytes, comm);
  note_bytes(x.send.capacity() + x.recv.capacity() + owner.capacity() * sizeof(owner[0]));
  release(x.send);
  agree(comm, [&] {
    rows.reserve(bytes > 0 ? x.recv.size() / bytes : 0);
    ByteReader reader(x.recv.data(), x.recv.size());
    while (!reader.done()) unpack_row(rows, reader);
    release(x.recv);
    rows.sort_unique_by_key();
  });
}

}  // namespace rondel
