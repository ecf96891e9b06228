#pragma once
// The rows of a CSV scene (scene.type = csv, SceneCsv.cpp) from a block of the file's text, so that each rank may
// read its own block (the app's FileScene) and the messages name the same line on any rank count.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/Config.hpp"
#include "core/Domain.hpp"
#include "core/SceneBuilder.hpp"

namespace rondel::scene_csv {

// Lines end in LF, CR LF or a lone CR (old Mac files); a UTF-8 byte order mark at the file's start is dropped. A
// block is whole LF-ended pieces of the file; `file_start`: it starts at the file's first byte.
// The number of lines of a block.
std::int64_t count_lines(std::string_view text, bool file_start);
// The file's first line with content (not blank, not a '#' comment) when it lies in this block: its text and number.
bool head_line(std::string_view text, bool file_start, std::int64_t first_line, std::string& head, std::int64_t& at);

struct Rows {
  std::vector<SceneDisc> discs;
  std::vector<std::int64_t> lines;  // each disc's line
};
// The discs of a block whose first line is number `first_line`; `head` (line `head_at`) is the file's first line with
// content, which says whether a header names the columns and whether fields are cut at commas. Throws InputError
// naming scene.file and the line of the first bad row of the block.
Rows rows(const SceneConfig& s, const std::string& head, std::int64_t head_at, std::string_view text, bool file_start,
          std::int64_t first_line);
// The discs of the whole file `path` of scene `s` on this process (a replicated scene's file: its tile), the ids
// checked distinct.
std::vector<SceneDisc> whole_file(const SceneConfig& s, const std::string& path);
// Rank `rank` of `ranks`'s block of a replicated scene (scene.replicate_x x scene.replicate_y copies of the discs
// `base` over `domain`): the ids [N rank / ranks, N (rank + 1) / ranks) of the copies numbered in rows across the
// whole box, the same discs as the whole replication's (scene::number_in_rows). It builds only the rows of the box
// that hold those ids (rows 2 R_max high, a disc's copies in one row whatever their column).
std::vector<SceneDisc> replicated_block(const SceneConfig& s, const Domain& domain, const std::vector<SceneDisc>& base,
                                        int rank, int ranks);
// The message for two discs of one id on lines `a` < `b` of scene.file.
std::string duplicate_message(const SceneConfig& s, std::int64_t gid, std::int64_t a, std::int64_t b);

}  // namespace rondel::scene_csv
