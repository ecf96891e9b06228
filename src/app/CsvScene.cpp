// scene.type = csv read in blocks (FileScene::csv): each rank reads its block of the file's bytes (the lines that
// start in it, parallel/TextBlocks.hpp), learns the number of its first line from the ranks before and the file's
// first line with content (a header, or the first row that says how many columns there are) from the rank that holds
// it, parses its rows (core/SceneCsv.hpp) and sends nothing: the discs go to their owners afterwards like any block
// (Simulation::route_to_owners). Ids are checked distinct in the global order of (id, line) (CanonicalOrder): no rank
// holds a list that grows with the file. Every message names the same line as the 1-rank read's.
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "app/Restart.hpp"
#include "core/Errors.hpp"
#include "core/InputFile.hpp"
#include "core/MemoryLimit.hpp"
#include "core/SceneCsv.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/ByteBuffer.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/TextBlocks.hpp"

namespace rondel {

namespace {

// The file's first line with content and its number, from the lowest rank that holds one; false when none does.
bool share_head(bool found, std::string& head, std::int64_t& at, const Communicator& comm) {
  const std::int64_t none = comm.size();
  const std::int64_t holder = -comm.max(found ? -static_cast<std::int64_t>(comm.rank()) : -none);
  if (holder == none) return false;
  std::vector<char> bytes;
  if (comm.rank() == holder) {
    bytes.resize(sizeof at + head.size());
    std::memcpy(bytes.data(), &at, sizeof at);
    std::memcpy(bytes.data() + sizeof at, head.data(), head.size());
  }
  comm.broadcast(bytes, static_cast<int>(holder));
  std::memcpy(&at, bytes.data(), sizeof at);
  head.assign(bytes.data() + sizeof at, bytes.size() - sizeof at);
  return true;
}

// Refuses two discs of one id, naming the lines of the first two of the smallest such id (as the 1-rank read does):
// in the global order of (id, line), each rank looks at the pairs that end in its range.
void check_distinct(const SceneConfig& s, const scene_csv::Rows& rows, const Communicator& comm) {
  CanonicalOrder order;
  order.arrange_keys(
      rows.discs.size(),
      [&](std::size_t i) {
        return OrderKey{rows.discs[i].gid, rows.lines[i]};
      },
      comm);
  ByteBuffer last;
  last.put(static_cast<std::uint8_t>(order.count() > 0));
  if (order.count() > 0) last.put(order.key(order.count() - 1));
  const std::vector<ByteBuffer> lasts = comm.all_gather(last);
  bool has_before = false;
  OrderKey before;
  for (int q = 0; q < comm.rank(); ++q) {
    ByteReader in(lasts[q].bytes.data(), lasts[q].bytes.size());
    if (in.get<std::uint8_t>() != 0) before = in.get<OrderKey>(), has_before = true;
  }
  OrderKey first_pair{std::numeric_limits<std::int64_t>::max(), 0}, second{0, 0};
  for (std::size_t k = 0; k < order.count(); ++k) {
    const OrderKey& key = order.key(k);
    if (has_before && before.a == key.a) {
      first_pair = before, second = key;
      break;
    }
    before = key, has_before = true;
  }
  ByteBuffer mine;
  mine.put(first_pair);
  mine.put(second);
  const std::vector<ByteBuffer> found = comm.all_gather(mine);
  for (const ByteBuffer& b : found) {  // the ranks in order: the first pair found is the smallest
    ByteReader in(b.bytes.data(), b.bytes.size());
    const OrderKey a = in.get<OrderKey>(), c = in.get<OrderKey>();
    if (a.a != std::numeric_limits<std::int64_t>::max())
      agree(comm, [&] { throw InputError(scene_csv::duplicate_message(s, a.a, a.b, c.b)); });
  }
}

}  // namespace

std::vector<SceneDisc> FileScene::csv(const SceneConfig& s, const std::string& path) const {
  if (s.replicate_x != 1 || s.replicate_y != 1) {
    // Every rank reads the file (the tile that is copied), and builds its block of the copies.
    std::vector<SceneDisc> block;
    agree(comm_, [&] {
      block =
          scene_csv::replicated_block(s, config_.domain, scene_csv::whole_file(s, path), comm_.rank(), comm_.size());
    });
    return block;
  }
  agree(comm_, [&] {
    // A rank holds its block: a file larger than the memory of all the ranks cannot become a scene.
    const std::uint64_t bound = memory_bound().bytes, P = static_cast<std::uint64_t>(comm_.size());
    const std::uint64_t most = bound == 0 || bound > UINT64_MAX / P ? UINT64_MAX : bound * P;
    if (const std::string why = input_file_problem(path, "scene.file", most); !why.empty()) throw InputError(why);
  });
  const std::string text = read_line_blocks(path, "scene.file", comm_);
  const bool start = comm_.root();  // rank 0's block starts at the file's first byte
  const std::int64_t first = first_line_number(scene_csv::count_lines(text, start), comm_);
  std::string head;
  std::int64_t head_at = 0;
  const bool found = scene_csv::head_line(text, start, first, head, head_at);
  if (!share_head(found, head, head_at, comm_)) return {};  // no line with content: an empty scene
  scene_csv::Rows rows;
  agree(comm_, [&] { rows = scene_csv::rows(s, head, head_at, text, start, first); });
  check_distinct(s, rows, comm_);
  return std::move(rows.discs);
}

}  // namespace rondel
