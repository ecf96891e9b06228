#pragma once
// A text file read by the ranks in blocks of its bytes (a CSV scene, a bond list): no rank holds the whole file.
#include <cstdint>
#include <string>

#include "parallel/Communicator.hpp"

namespace rondel {

// Collective. Rank r reads bytes [S r/P, S (r+1)/P) of the S-byte file `path` (MPI-IO, independent reads) and keeps
// the lines that start in them: the head of its block up to the first '\n' goes to the rank that holds the start of
// that line (a block without any '\n' goes whole), point to point. The result is whole lines, each ending in '\n'
// but the file's last; rank 0's starts at the file's first byte, and the blocks of ranks 0, 1, ... make the file (a
// file of one line is held by one rank). `what` names the file in the messages ("scene.file"): a file that cannot be
// opened or read is refused as InputError on every rank.
std::string read_line_blocks(const std::string& path, const std::string& what, const Communicator& comm);

// Collective: the number of the first line of this rank's block, 1 + the `lines` of the ranks before.
std::int64_t first_line_number(std::int64_t lines, const Communicator& comm);

}  // namespace rondel
