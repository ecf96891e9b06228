// The distributed file order of checkpoints (parallel/CanonicalOrder.hpp): records in ascending key order
// over the ranks, each rank's first row the prefix sum of the counts before it, the records' bytes intact,
// the ranges balanced within the sample sort's bound, the structures' bytes falling as 1/P; errors on the
// last rank only (a duplicate key, a bad dataset block) thrown on every rank instead of a hang; and the rows
// of a restart routed to the owners of their discs through the distributed gid directory.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Errors.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/OrderedText.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {
namespace {

using partest::all_ranks;
using partest::world_rank;
using partest::world_size;

// How the keys are spread over the ranks.
enum class Spread { interleaved, round_robin, all_on_last, reversed_blocks };

// Rank r's keys among n in all: interleaved (the first rank holding three times the share of the others),
// round robin (key k on rank k mod P), all on the last rank, or in blocks that all belong to another
// rank's range.
std::vector<OrderKey> keys_for(Spread spread, std::int64_t n, int rank, int ranks) {
  std::vector<OrderKey> keys;
  for (std::int64_t k = 0; k < n; ++k) {
    int owner = 0;
    if (spread == Spread::interleaved)
      owner = (k % (ranks + 2) < 3) ? 0 : static_cast<int>(k % (ranks + 2)) - 2;
    else if (spread == Spread::round_robin)
      owner = static_cast<int>(k % ranks);
    else if (spread == Spread::all_on_last)
      owner = ranks - 1;
    else
      owner = ranks - 1 - static_cast<int>(k * ranks / n);
    // Contact-like keys (lo, hi), in a scrambled local order.
    if (owner == rank) keys.push_back({k / 3, 7 * k});
  }
  std::reverse(keys.begin(), keys.end());
  return keys;
}

// A record: the key's two numbers and the rank it came from.
constexpr std::size_t kRecord = 2 * sizeof(std::int64_t) + sizeof(std::int32_t);

struct Arranged {
  std::vector<std::int64_t> mine;  // a, b of each record of this rank's range, in order
  std::uint64_t offset = 0, count = 0, total = 0;
  bool bytes_ok = true;
};

Arranged arrange(CanonicalOrder& order, const std::vector<OrderKey>& keys, const Communicator& comm) {
  const std::int32_t me = comm.rank();
  order.arrange(
      keys, kRecord,
      [&](std::size_t i, char* out) {
        std::memcpy(out, &keys[i].a, 8), std::memcpy(out + 8, &keys[i].b, 8), std::memcpy(out + 16, &me, 4);
      },
      comm);
  Arranged a{{}, order.offset(), order.count(), order.total(), true};
  for (std::size_t k = 0; k < order.count(); ++k) {
    OrderKey key;
    std::int32_t from = me;
    if (order.is_local(k)) {
      key = keys[order.local_index(k)];
    } else {
      std::memcpy(&key.a, order.received(k), 8), std::memcpy(&key.b, order.received(k) + 8, 8);
      std::memcpy(&from, order.received(k) + 16, 4);
      a.bytes_ok = a.bytes_ok && from != me && from >= 0 && from < comm.size();
    }
    a.bytes_ok = a.bytes_ok && key == order.key(k);
    a.mine.push_back(key.a), a.mine.push_back(key.b);
  }
  return a;
}

void expect_global_order(Spread spread, std::int64_t n) {
  const Communicator comm;
  const std::vector<OrderKey> keys = keys_for(spread, n, comm.rank(), comm.size());
  CanonicalOrder order;
  for (int pass = 0; pass < 2; ++pass) {  // the second reuses the buffers
    const Arranged a = arrange(order, keys, comm);
    EXPECT_TRUE(a.bytes_ok) << "a record's bytes or key came back changed";
    EXPECT_EQ(a.total, static_cast<std::uint64_t>(n));
    std::uint64_t before = 0, count = a.count;
    MPI_Exscan(&count, &before, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(a.offset, comm.rank() == 0 ? 0 : before) << "the first row is not the prefix sum of the counts";
    // The sample sort's bound: N/P + N/64 (plus rounding).
    EXPECT_LE(a.count, static_cast<std::uint64_t>(n / comm.size() + n / 64 + 2)) << "on rank " << comm.rank();
    // Rank 0 checks the concatenation in rank order against the sorted keys of every rank.
    std::vector<int> sizes(comm.size()), at(comm.size(), 0);
    int mine = static_cast<int>(a.mine.size());
    MPI_Gather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    for (int r = 1; r < comm.size(); ++r) at[r] = at[r - 1] + sizes[r - 1];
    std::vector<std::int64_t> all(comm.root() ? 2 * n : 0);
    MPI_Gatherv(a.mine.data(), mine, MPI_INT64_T, all.data(), sizes.data(), at.data(), MPI_INT64_T, 0, MPI_COMM_WORLD);
    if (comm.root()) {
      std::vector<OrderKey> expected;
      for (int r = 0; r < comm.size(); ++r)
        for (const OrderKey& k : keys_for(spread, n, r, comm.size())) expected.push_back(k);
      std::sort(expected.begin(), expected.end());
      ASSERT_EQ(all.size(), 2 * expected.size());
      for (std::size_t k = 0; k < expected.size(); ++k)
        ASSERT_TRUE(all[2 * k] == expected[k].a && all[2 * k + 1] == expected[k].b) << "row " << k << " out of order";
    }
  }
}

TEST(CanonicalOrder, InterleavedKeysEndInGlobalOrderAtPrefixSumOffsets) {
  expect_global_order(Spread::interleaved, 20011);
}

TEST(CanonicalOrder, RoundRobinKeysEndInGlobalOrder) { expect_global_order(Spread::round_robin, 7777); }

TEST(CanonicalOrder, KeysAllOnOneRankAreSpreadOverEveryRank) { expect_global_order(Spread::all_on_last, 9001); }

TEST(CanonicalOrder, BlocksThatAllMoveArriveWhole) { expect_global_order(Spread::reversed_blocks, 12345); }

TEST(CanonicalOrder, NoRecordsAnywhere) { expect_global_order(Spread::interleaved, 0); }

// A checkpoint's way: the keys first, then one dataset at a time, each exchange of its own size replacing the last.
TEST(CanonicalOrder, ExchangesAfterTheKeysBringEachRecordsBytesOfThatExchange) {
  const Communicator comm;
  const std::int32_t me = comm.rank();
  for (const Spread spread : {Spread::interleaved, Spread::reversed_blocks}) {
    const std::vector<OrderKey> keys = keys_for(spread, 5003, comm.rank(), comm.size());
    CanonicalOrder order;
    order.arrange_keys(
        keys.size(), [&keys](std::size_t i) { return keys[i]; }, comm);
    std::int64_t wrong = 0, remote = 0;
    order.exchange(
        sizeof(std::int64_t), [&](std::size_t i, char* out) { std::memcpy(out, &keys[i].b, 8); }, comm);
    for (std::size_t k = 0; k < order.count(); ++k) {
      std::int64_t b = 0;
      if (order.is_local(k))
        b = keys[order.local_index(k)].b;
      else
        std::memcpy(&b, order.received(k), 8), ++remote;
      wrong += b != order.key(k).b;
    }
    order.exchange(
        sizeof me, [&](std::size_t, char* out) { std::memcpy(out, &me, sizeof me); }, comm);
    for (std::size_t k = 0; k < order.count(); ++k) {
      std::int32_t from = me;
      if (!order.is_local(k)) std::memcpy(&from, order.received(k), sizeof from);
      wrong += order.is_local(k) ? 0 : (from == me || from < 0 || from >= comm.size());
    }
    EXPECT_EQ(comm.sum(wrong), 0) << "a record's bytes did not follow its key";
    if (comm.size() > 1) {
      EXPECT_GT(comm.sum(remote), 0) << "no record changed rank: the test shows nothing";
    }
    order.release();
    EXPECT_EQ(order.capacity_bytes(), 0u) << "release() keeps a buffer";
  }
}

// A text file in ranks' blocks, each written in pieces of a few lines: the lines in global key order, each once.
TEST(CanonicalOrder, OrderedTextWrittenInSmallPiecesHoldsEveryLineInOrder) {
  const Communicator comm;
  std::string path;
  if (comm.root())
    path = (std::filesystem::temp_directory_path() / ("rondel-text-" + std::to_string(::getpid()) + ".csv")).string();
  path = partest::broadcast(path);
  const std::vector<OrderKey> keys = keys_for(Spread::interleaved, 1001, comm.rank(), comm.size());
  CanonicalOrder order;
  order.arrange_keys(
      keys.size(), [&keys](std::size_t i) { return keys[i]; }, comm);
  for (const std::size_t piece : {std::size_t{1}, std::size_t{40}, std::size_t{1} << 20}) {
    write_ordered_text(
        path, "a,b\n", order,
        [&](std::size_t k, std::string& out) {
          out += std::to_string(order.key(k).a) + "," + std::to_string(order.key(k).b) + "\n";
        },
        comm, piece);
    if (comm.root()) {
      std::vector<OrderKey> all;
      for (int r = 0; r < comm.size(); ++r)
        for (const OrderKey& k : keys_for(Spread::interleaved, 1001, r, comm.size())) all.push_back(k);
      std::sort(all.begin(), all.end());
      std::string expected = "a,b\n";
      for (const OrderKey& k : all) expected += std::to_string(k.a) + "," + std::to_string(k.b) + "\n";
      std::ifstream in(path, std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      EXPECT_EQ(text, expected) << "pieces of " << piece << " bytes";
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  if (comm.root()) std::filesystem::remove(path);
}

// The largest rank's structure bytes when world ranks 0 .. ranks-1 arrange `total` keys.
double structure_bytes(int ranks, std::int64_t total) {
  MPI_Comm raw = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < ranks ? 0 : MPI_UNDEFINED, world_rank(), &raw);
  double bytes = 0.0;
  if (raw != MPI_COMM_NULL) {
    {
      const Communicator comm(raw);
      CanonicalOrder order;
      // Every rank holds N/P keys, and all but 1/P of them move.
      const std::vector<OrderKey> keys = keys_for(Spread::round_robin, total, comm.rank(), comm.size());
      arrange(order, keys, comm);
      bytes = static_cast<double>(order.capacity_bytes() + keys.capacity() * sizeof(OrderKey));
    }
    MPI_Comm_free(&raw);
  }
  MPI_Allreduce(MPI_IN_PLACE, &bytes, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return bytes;
}

TEST(CanonicalOrder, StructureBytesFallAsOneOverRanks) {
  if (world_size() < 2) GTEST_SKIP() << "needs 2 or more ranks";
  // Strong: a fixed total, from 2 ranks to all. The share of records that move grows from 1/2 to
  // (P - 1)/P with round-robin keys (all but 1/P move), which adds at most 2 x 36 / 84 B per record:
  // the bytes fall as 1/P within 30 %.
  constexpr std::int64_t kTotal = 200000;
  const double two = structure_bytes(2, kTotal), all = structure_bytes(world_size(), kTotal);
  EXPECT_LE(all, 1.3 * two * 2.0 / world_size() + 65536.0)
      << "2 ranks: " << two << " B, " << world_size() << " ranks: " << all << " B";
  // Weak: a fixed size per rank stays flat within 30 % (the same growing share that moves).
  const double weak_two = structure_bytes(2, 2 * 50000), weak_all = structure_bytes(world_size(), world_size() * 50000);
  EXPECT_LE(weak_all, 1.3 * weak_two) << "2 ranks: " << weak_two << " B, " << world_size() << " ranks: " << weak_all;
  // And per record: 24 B of order (48 B while merging) + 2 x (16 B key + 20 B record) sent and received.
  const double per_record = all * world_size() / kTotal;
  EXPECT_LE(per_record, 1.15 * (48.0 + 2.0 * 36.0) + 65536.0 * world_size() / kTotal) << per_record << " B";
}

TEST(CanonicalOrder, ADuplicateKeyOnTheLastRankStopsEveryRank) {
  const Communicator comm;
  std::vector<OrderKey> keys = keys_for(Spread::interleaved, 1000, comm.rank(), comm.size());
  if (comm.rank() == comm.size() - 1) keys.push_back(keys.front());
  CanonicalOrder order;
  std::string message;
  try {
    arrange(order, keys, comm);
  } catch (const std::exception& e) {
    message = e.what();
  }
  const std::string last = "on rank " + std::to_string(comm.size() - 1);
  EXPECT_TRUE(all_ranks(message.find("occurs twice") != std::string::npos && message.find(last) != std::string::npos))
      << "rank " << comm.rank() << " got: '" << message << "'";
}

TEST(CanonicalOrder, ADatasetBlockFailingOnTheLastRankStopsEveryRank) {
  const Communicator comm;
  std::string path;
  if (comm.root())
    path = (std::filesystem::temp_directory_path() / ("rondel-order-" + std::to_string(::getpid()) + ".h5")).string();
  path = partest::broadcast(path);
  std::string message;
  try {
    Hdf5File f(path, Hdf5File::Mode::create, comm);
    f.run([&] {
      const std::vector<double> block(10, 1.0);
      const std::uint64_t total = 10 * static_cast<std::uint64_t>(comm.size());
      // The last rank's block lies past the end of the dataset.
      const std::uint64_t offset = comm.rank() == comm.size() - 1 ? total : 10 * comm.rank();
      f.write("/values", block, total, offset);
      f.write_attribute("/", "never", std::int64_t{1});
    });
  } catch (const IoError& e) {
    message = e.what();
  }
  EXPECT_TRUE(all_ranks(message.find("outside dataset /values") != std::string::npos))
      << "rank " << comm.rank() << " got: '" << message << "'";
  MPI_Barrier(MPI_COMM_WORLD);
  if (comm.root()) std::filesystem::remove(path);
}

}  // namespace
}  // namespace rondel

namespace rondel {
namespace {

// route_rows_to_owners through the distributed gid directory: gid g is owned by rank (g + 1) mod P (never
// its home rank g mod P, from 2 ranks on); rank r starts with the rows (g, g + 1) of g = r mod P and a
// copy of row (0, 1) everywhere, plus rows whose disc 1 (1000 + g) no rank owns. Afterwards each rank
// holds exactly the rows of which it owns an end (disc pairs) or disc 1 (wall rows), once, with history.
TEST(RouteRows, EveryRowReachesTheOwnersOfItsDiscsThroughTheDirectory) {
  const Communicator comm;
  const int ranks = comm.size(), me = comm.rank();
  constexpr std::int64_t kDiscs = 60;
  auto owner = [ranks](std::int64_t g) { return static_cast<int>((g + 1) % ranks); };
  DiscStore discs;
  for (std::int64_t g = 0; g < kDiscs; ++g)
    if (owner(g) == me) discs.gid.push_back(g);
  discs.set_owned_count(discs.gid.size());
  for (const bool both_ends : {true, false}) {
    ContactTable rows({"xi"}, false);
    auto add = [&rows](std::int64_t lo, std::int64_t hi) {
      rows.push({lo, hi}, -1, -1, 0);
      rows.slot[0].back() = static_cast<double>(lo * 1000 + hi);
    };
    for (std::int64_t g = me; g + 1 < kDiscs; g += ranks) add(g, g + 1);
    add(0, 1);             // on every rank: one copy survives
    add(1000 + me, 5);     // disc 1 owned by no rank
    add(2000 + me, 3000);  // neither disc owned: dropped
    route_rows_to_owners(rows, both_ends, discs, comm);
    std::vector<ContactKey> expected;
    for (std::int64_t g = 0; g + 1 < kDiscs; ++g)
      if (owner(g) == me || (both_ends && owner(g + 1) == me)) expected.push_back({g, g + 1});
    for (int r = 0; r < ranks && both_ends; ++r)
      if (owner(5) == me) expected.push_back({1000 + r, 5});
    std::sort(expected.begin(), expected.end());
    bool same = rows.key == expected;
    for (std::size_t k = 0; k < rows.size(); ++k)
      same = same && rows.slot[0][k] == static_cast<double>(rows.key[k].lo * 1000 + rows.key[k].hi);
    EXPECT_TRUE(same) << "rank " << me << (both_ends ? " (disc pairs)" : " (wall rows)") << ": " << rows.size()
                      << " rows, expected " << expected.size();
  }
}

}  // namespace
}  // namespace rondel
