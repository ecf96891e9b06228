#pragma once
// The pairs of bonds.file (docs/bonds.md): a CSV of 'gid1,gid2' lines, '#' comments and blank lines skipped, an
// optional header 'gid1,gid2'. Each rank reads a block of its bytes (the lines that start in it), so no rank holds the
// whole list; the pairs then go to the owners of their discs (Simulation::create_bonds).
#include <string>

#include "core/ContactTable.hpp"
#include "parallel/Communicator.hpp"

namespace rondel::bond_list {

// This rank's block of the file's pairs as rows of a bond table keyed (lower gid, higher gid), local indices -1, with
// each row's line number in its Fb_n column (for the messages of the checks that follow; the caller zeroes it).
// Collective; a line that is not two distinct ids in [0, 2^53) is refused naming the file and the line, the same
// message on any rank count (the first such line).
void read_block(const std::string& path, ContactTable& rows, const Communicator& comm);

}  // namespace rondel::bond_list
