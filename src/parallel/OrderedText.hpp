#pragma once
#include <cstddef>
#include <functional>
#include <string>

#include "parallel/CanonicalOrder.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// Writes a text file whose lines follow the global order of `order` (CanonicalOrder, already arranged):
// each rank measures the lines of its block (`line(k, out)` appends the k-th record's line; it is called twice
// per line and must give the same line), a prefix sum of the blocks' lengths gives each rank its byte offset, and
// every rank formats its block again and writes it with MPI-IO at that offset, in pieces of about `piece` bytes (a
// piece ends at the first line end past it; 64 MiB unless a test asks for less). No rank
// holds more than a piece of text, so the file may be larger than all the ranks' memory. `header` comes first (rank 0).
// Collective; a failure on any rank is agreed and thrown on every rank as IoError naming the file; the partial file is
// removed.
void write_ordered_text(const std::string& path, const std::string& header, const CanonicalOrder& order,
                        const std::function<void(std::size_t, std::string&)>& line, const Communicator& comm,
                        std::size_t piece = std::size_t{1} << 26);

}  // namespace rondel
