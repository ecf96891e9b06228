#include "app/BondList.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/DiscStore.hpp"
#include "core/Errors.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/ByteBuffer.hpp"

namespace rondel::bond_list {

namespace {

// The file's bytes from `begin` to the end of the line that holds byte `end` - 1: the lines that start in
// [begin, end), after the rest of the line that holds byte begin - 1 (read by the block before).
std::string block_text(std::ifstream& in, std::uint64_t size, std::uint64_t begin, std::uint64_t end) {
  std::string text;
  if (begin >= end) return text;
  const std::uint64_t from = begin == 0 ? 0 : begin - 1;
  in.seekg(static_cast<std::streamoff>(from));
  std::string line;
  if (begin > 0) std::getline(in, line);  // the line that byte begin - 1 ends or is in belongs to the block before
  std::uint64_t at = static_cast<std::uint64_t>(in.tellg());
  if (!in || at >= end || at >= size) return text;
  while (at < end && std::getline(in, line)) {
    text += line;
    text += '\n';
    at += line.size() + 1;
  }
  return text;
}

bool parse_id(const std::string& field, std::int64_t& id) {
  const auto first = field.find_first_not_of(" \t\r"), last = field.find_last_not_of(" \t\r");
  if (first == std::string::npos) return false;
  const char* b = field.data() + first;
  const char* e = field.data() + last + 1;
  const auto [p, ec] = std::from_chars(b, e, id);
  return ec == std::errc() && p == e && id >= 0 && id < kMaxGid;
}

}  // namespace

void read_block(const std::string& path, ContactTable& rows, const Communicator& comm) {
  std::string text;
  std::uint64_t size = 0;
  agree(comm, [&] {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw InputError("bonds.file '" + path + "' cannot be read");
    size = static_cast<std::uint64_t>(in.tellg());
    const auto P = static_cast<std::uint64_t>(comm.size()), r = static_cast<std::uint64_t>(comm.rank());
    text = block_text(in, size, size * r / P, size * (r + 1) / P);
  });
  // The first line of this block: the lines of the blocks before, counted there.
  ByteBuffer mine;
  mine.put(static_cast<std::int64_t>(std::count(text.begin(), text.end(), '\n')));
  std::int64_t line = 1;
  const std::vector<ByteBuffer> counts = comm.all_gather(mine);
  for (int k = 0; k < comm.rank(); ++k)
    line += ByteReader(counts[k].bytes.data(), counts[k].bytes.size()).get<std::int64_t>();
  agree(comm, [&] {
    std::size_t at = 0;
    for (; at < text.size(); ++line) {
      const std::size_t nl = text.find('\n', at);
      const std::string l = text.substr(at, nl - at);
      at = nl + 1;
      const auto first = l.find_first_not_of(" \t\r");
      if (first == std::string::npos || l[first] == '#') continue;
      const std::size_t comma = l.find(',');
      std::int64_t a = 0, b = 0;
      const bool two = comma != std::string::npos && l.find(',', comma + 1) == std::string::npos;
      if (line == 1 && two && l.substr(0, comma).find("gid1") != std::string::npos) continue;  // the header
      if (!two || !parse_id(l.substr(0, comma), a) || !parse_id(l.substr(comma + 1), b) || a == b)
        throw InputError("bonds.file '" + path + "' line " + std::to_string(line) + ": '" + l +
                         "' is not a pair 'gid1,gid2' of two different disc ids (integers in [0, 2^53))");
      rows.push({std::min(a, b), std::max(a, b)}, -1, -1, -1);
      rows.slot[0].back() = static_cast<double>(line);
    }
  });
}

}  // namespace rondel::bond_list
