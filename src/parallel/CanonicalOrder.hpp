#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "parallel/ByteBuffer.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// A block of the global ascending order of records spread over ranks: rank r holds records
// [offset, offset + count) of `total`, in order. This is how files get a content independent of the rank
// count (discs by gid, contacts by key).
struct OrderedBlock {
  std::uint64_t total = 0, offset = 0, count = 0;
  std::vector<char> records;  // count records of the fixed size, ascending key
};

// Rows [r total/P, (r+1) total/P) go to rank r.
inline std::uint64_t block_begin(std::uint64_t total, int rank, int ranks) {
  return total * static_cast<std::uint64_t>(rank) / static_cast<std::uint64_t>(ranks);
}

// Redistributes fixed-size records (keys unique over all ranks) into ordered blocks: the keys are gathered
// on every rank to find each record's global index, then each record is sent to the rank of its block.
template <class Key>
OrderedBlock order_into_blocks(const std::vector<Key>& keys, const std::vector<char>& records, std::size_t bytes,
                               const Communicator& comm) {
  ByteBuffer mine;
  for (const Key& k : keys) mine.put(k);
  std::vector<Key> all;
  for (const ByteBuffer& b : comm.all_gather(mine)) {
    ByteReader r(b.bytes.data(), b.bytes.size());
    while (!r.done()) all.push_back(r.template get<Key>());
  }
  std::sort(all.begin(), all.end());
  OrderedBlock block;
  block.total = all.size();
  block.offset = block_begin(block.total, comm.rank(), comm.size());
  block.count = block_begin(block.total, comm.rank() + 1, comm.size()) - block.offset;
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.size()));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const auto index = static_cast<std::uint64_t>(std::lower_bound(all.begin(), all.end(), keys[k]) - all.begin());
    int dest = 0;
    while (dest + 1 < comm.size() && block_begin(block.total, dest + 1, comm.size()) <= index) ++dest;
    out[dest].put(index);
    const std::size_t at = out[dest].bytes.size();
    out[dest].bytes.resize(at + bytes);
    std::copy(records.begin() + k * bytes, records.begin() + (k + 1) * bytes, out[dest].bytes.begin() + at);
  }
  block.records.resize(block.count * bytes);
  for (const ByteBuffer& b : comm.all_to_all(out)) {
    for (std::size_t at = 0; at < b.bytes.size(); at += sizeof(std::uint64_t) + bytes) {
      std::uint64_t index = 0;
      std::memcpy(&index, b.bytes.data() + at, sizeof index);
      std::memcpy(block.records.data() + (index - block.offset) * bytes, b.bytes.data() + at + sizeof index, bytes);
    }
  }
  return block;
}

}  // namespace rondel
