#include "app/BondList.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/DiscStore.hpp"
#include "core/Errors.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/TextBlocks.hpp"

namespace rondel::bond_list {

namespace {

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
  const std::string text = read_line_blocks(path, "bonds.file", comm);
  // The first line of this block: the lines of the blocks before, counted there.
  std::int64_t lines = std::count(text.begin(), text.end(), '\n');
  if (!text.empty() && text.back() != '\n') ++lines;  // the file's last line, without its '\n'
  std::int64_t line = first_line_number(lines, comm);
  agree(comm, [&] {
    std::size_t at = 0;
    for (; at < text.size(); ++line) {
      const std::size_t nl = std::min(text.find('\n', at), text.size());
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
