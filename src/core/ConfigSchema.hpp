#pragma once
#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "core/LawSpec.hpp"

namespace rondel {

// Every configuration key, declared once with its default, unit and meaning (docs/design.md section 8); the
// law blocks come from the catalog (each law declares its parameters next to its equations).
boost::program_options::options_description config_schema(const LawCatalog& laws);

// The sections whose names the user chooses (docs/physics.md section 7): [material.NAME] and the pair blocks
// [BLOCK.A.B] (disc-disc), [BLOCK.A.wall.W] (disc-wall), where BLOCK is a law block or `contact` (its
// per-pair `rolling` switch). Found in the INI text and the command line before the parse.
struct DynamicSections {
  std::vector<std::string> materials;  // NAME of each [material.NAME]
  std::vector<std::string> pairs;      // "BLOCK.A.B" or "BLOCK.A.wall.W"
};
// The names of the dynamic sections that the keys `full_keys` ("section.key") use.
DynamicSections dynamic_sections(const LawCatalog& laws, const std::vector<std::string>& full_keys);
// The keys of an INI text and of command-line arguments, as "section.key".
std::vector<std::string> ini_keys(const std::string& ini_text);
std::vector<std::string> argument_keys(const std::vector<std::string>& args);
// The schema with the dynamic sections added; `help` adds them once with the placeholders NAME, A, B, W.
boost::program_options::options_description config_schema(const LawCatalog& laws, const DynamicSections& dynamic,
                                                          bool help = false);

// What a key holds, declared with the key itself (core/KeyTable.hpp: the same row as the schema): the validation
// pass checks every value given against it before anything is read (docs/design.md section 8), and the tests walk
// it.
enum class KeyType { real, integer, flag, text, choice, words, numbers, records };
struct KeySpec {
  std::string key;
  KeyType type;
  Range range;                       // real, integer: the value's; numbers, records: every number's
  std::vector<std::string> allowed;  // choice: the words allowed; words: each word's (any when empty)
};
// Every key of config_schema(laws, dynamic) with its type and range.
std::vector<KeySpec> config_keys(const LawCatalog& laws, const DynamicSections& dynamic = {});
// The declared key closest to `name` by edit distance ("" when none is close): "did you mean ...?".
std::string closest_key(const std::string& name, const std::vector<KeySpec>& keys);

}  // namespace rondel
