#pragma once
// Plain descriptors of a contact law as the configuration layer sees it: its keyword, its INI block
// (section, title line, parameters) and, per parameter, its unit, default, allowed range, help line and
// the ContactParams field it fills. The law types in src/physics declare these next to their equations;
// the registry (physics/LawRegistry) hands the whole catalog to the parser, which lives here in core and
// may not include physics.
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "core/ContactParams.hpp"

namespace rondel {

// An interval of allowed values; a value must also be finite.
struct Range {
  double lo = 0.0, hi = INFINITY;
  bool lo_open = false, hi_open = true;
  bool contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string text() const;  // "> 0", ">= 0", "in (0, 1]"
};
inline constexpr Range kPositive{0.0, INFINITY, true, true};
inline constexpr Range kNonNegative{0.0, INFINITY, false, true};
inline constexpr Range kRestitution{0.0, 1.0, true, false};

// required: the key must be given when the law is selected; defaulted: `def` applies; optional: no
// default, the field keeps its ContactParams value unless the key is given.
enum class Presence { required, defaulted, optional };

struct ParamSpec {
  const char* key;   // within the block, e.g. "k_r"
  const char* unit;  // e.g. "N/m", "-"
  Presence presence;
  // defaulted: the default; optional: the value that means "not given" (the field's value when the key is absent)
  double def;
  Range range;
  const char* help;  // one line, without unit, requirement or range (those are added)
  double ContactParams::*target;
  // A value for the reference contact of docs/developing.md (two discs of 5 mm, k_n = 1e6 N/m, mu = 0.5: the
  // validation cases' disc D5 and contact set S): the law conformance tests run every law with these (NaN: the
  // default, or for an optional key not given).
  double example = NAN;
  // A word-valued parameter: the words it allows, its value the word's index (`def`, `example` and `range` are
  // indices). Empty: a number.
  std::span<const char* const> words = {};
  // The text of a value: the word of a word-valued parameter, else the number.
  std::string text(double value) const;
  // The index of `word` in `words`; -1 when it is not one.
  int word_index(const std::string& word) const;
};

// One [section] of law parameters. Several laws may share a block (jiang_plastic and jiang_brittle).
struct LawBlock {
  const char* section;
  const char* title;  // the --help heading after "[section] "
  std::span<const ParamSpec> params;
  // Keys of which at most one may be given (the linear law's damping: zeta, c_n or e). In a pair block, the one
  // given replaces the default's: the others return to their "not given" value.
  std::span<const char* const> one_of = {};
  // One key of one_of must be given (walton_braun: e or K2); else none need be (linear: zeta 0 by default).
  bool one_of_required = false;
  const ParamSpec* find(const std::string& key) const;
  // Every parameter at its example value (ParamSpec::example), or its default when it has no example.
  ContactParams with_examples(ContactParams p) const;
  // The command-line options that set the parameters of with_examples ("--wang.k_r=30000", ...).
  std::vector<std::string> example_options() const;
  bool in_one_of(const std::string& key) const;
};

// One law of a kind: its keyword, its block (nullptr: no parameters) and what it needs of the rest of the
// configuration, as the law declares it (physics/LawConcepts.hpp).
struct LawInfo {
  const char* keyword;
  const LawBlock* block;
  bool elastic = false;                // it needs every material's youngs_modulus and poisson_ratio
  bool stiffening = false;             // a normal law whose stiffness grows with the overlap (the critical step takes
                                       // it at run.max_overlap)
  const char* needs_normal = nullptr;  // it works only with this normal law (nullptr: any)
  const char* needs_why = "";          // why, for the message
};

// The laws of one kind, selected by the key contact.<kind>; the first law is the default.
struct LawKind {
  const char* kind;  // "normal", "tangential", "rolling"
  std::vector<LawInfo> laws;
  std::string keywords() const;  // "a | b | c", in registry order
  const LawInfo* find(const std::string& keyword) const;
};

struct LawCatalog {
  LawKind normal, tangential, rolling;
  // The parallel bonds' block [bonds] (nullptr: a catalog without bonds): not a law of a kind, but a block of pair
  // parameters read like one, when any of its keys is given.
  const LawBlock* bonds = nullptr;
  std::vector<const LawKind*> kinds() const { return {&normal, &tangential, &rolling}; }
  // Every distinct block, in registry order (normal, tangential, rolling), then the bonds' block.
  std::vector<const LawBlock*> blocks() const;
};

}  // namespace rondel
