#pragma once
#include <cstddef>
#include <functional>
#include <string>

#include "parallel/CanonicalOrder.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// Writes a text file whose lines follow the global order of `order` (CanonicalOrder, already arranged):
// each rank formats the lines of its block (`line(k, out)` appends the k-th record's line), a prefix sum of
// the blocks' lengths gives each rank its byte offset, and every rank writes its block collectively with
// MPI-IO at that offset, in pieces of at most 1 GiB. No rank holds another rank's lines, so the file may be
// larger than any rank's memory. `header` comes first (rank 0). Collective; a failure on any rank is agreed
// and thrown on every rank as IoError naming the file; the partial file is removed.
void write_ordered_text(const std::string& path, const std::string& header, const CanonicalOrder& order,
                        const std::function<void(std::size_t, std::string&)>& line, const Communicator& comm);

}  // namespace rondel
