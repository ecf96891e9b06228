// [contact], the law blocks and [wall_contact]. Which laws exist, their keywords, blocks and parameters come from
// the law catalog (physics/LawRegistry); the rows of ConfigSchema.cpp read the selected keywords. What is written
// here applies to any law: a block of an unselected law is refused, a block's parameters fill ContactParams through
// their ParamSpec, at most one key of a block's one_of group is given (one where the block requires it), and
// [wall_contact] takes only keys that the selected laws' blocks have.
#include <string>

#include "core/ConfigRead.hpp"

namespace rondel::config {

namespace {

// The Config fields of the selected keywords, in the catalog's order of kinds (normal, tangential, rolling).
std::string Config::*const kSelected[] = {&Config::normal_law, &Config::tangential_law, &Config::rolling_law};

const std::string& selected_keyword(const LawCatalog& laws, const Config& c, const LawKind& kind) {
  const auto kinds = laws.kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k)
    if (kinds[k] == &kind) return c.*kSelected[k];
  throw ConfigError(std::string("internal: a law kind not in the catalog: ") + kind.kind);
}
const LawBlock* selected_block(const LawCatalog& laws, const Config& c, const LawKind& kind) {
  const LawInfo* law = kind.find(selected_keyword(laws, c, kind));
  return law ? law->block : nullptr;
}

// The kind whose laws use the block named `section`; nullptr when it is not a law block.
const LawKind* block_kind(const LawCatalog& laws, const std::string& section) {
  for (const LawKind* kind : laws.kinds())
    for (const LawInfo& law : kind->laws)
      if (law.block && section == law.block->section) return kind;
  return nullptr;
}

// A parameter block for a law that is not selected is a mistake (a typo in the law, or a stale block).
void refuse_unselected_blocks(const LawCatalog& laws, const Reader& r, const Config& c) {
  for (const auto& [key, value] : r.vm) {
    const std::string section = key.substr(0, key.find('.'));
    const LawKind* kind = block_kind(laws, section);
    if (!kind || value.defaulted()) continue;
    const LawBlock* block = selected_block(laws, c, *kind);
    if (!block || section != block->section)
      throw ConfigError("key '" + key + "' belongs to the [" + section + "] block, but that law is not selected (" +
                        "contact." + kind->kind + " = " + selected_keyword(laws, c, *kind) + ")");
  }
}

// Every parameter of the selected law's block, in declaration order, into p.
void read_block(const Reader& r, const LawKind& kind, const std::string& law, const LawBlock& block, ContactParams& p) {
  int one_of = 0;
  for (const ParamSpec& spec : block.params) {
    const std::string key = std::string(block.section) + "." + spec.key;
    if (!r.vm.count(key)) {
      if (spec.presence == Presence::required)
        r.required(key, " (required with contact." + std::string(kind.kind) + " = " + law + ")");
      continue;
    }
    if (block.in_one_of(spec.key)) ++one_of;
    p.*spec.target = law_param(r, key, spec);
  }
  if (one_of > 1 || (one_of == 0 && block.one_of_required)) {
    std::string keys;
    for (const char* k : block.one_of)
      keys += (keys.empty() ? "'" : ", '") + std::string(block.section) + "." + k + "'";
    if (one_of > 1) throw ConfigError("keys " + keys + ": give at most one");
    throw ConfigError("keys " + keys + ": give one (required with contact." + std::string(kind.kind) + " = " + law +
                      ")");
  }
}

// The pair block of a law at walls, for a message: "[coulomb.MATERIAL.wall.WALL_MATERIAL]".
std::string wall_block_hint(const LawBlock* block) {
  return std::string(block ? block->section : "BLOCK") + ".MATERIAL.wall.WALL_MATERIAL";
}

// [wall_contact]: the disc-disc parameters p with the keys given here replacing theirs. A key needs a selected
// law whose block has the parameter of that name.
ContactParams read_wall_contact(const LawCatalog& laws, const Reader& r, const Config& c, const ContactParams& p) {
  ContactParams w = p;
  w.rolling = r.get<bool>("wall_contact.rolling");
  const LawBlock* normal = selected_block(laws, c, laws.normal);
  const LawBlock* tangential = selected_block(laws, c, laws.tangential);
  if (r.vm.count("wall_contact.zeta") && r.vm.count("wall_contact.e"))
    throw ConfigError("keys 'wall_contact.zeta' and 'wall_contact.e': give at most one");
  // The keys [wall_contact] takes, and the kind of law whose block has them.
  struct WallKey {
    const char* name;
    bool normal;
  };
  for (const WallKey& wk :
       {WallKey{"k_n", true}, WallKey{"zeta", true}, WallKey{"e", true}, WallKey{"k_s", false}, WallKey{"mu", false}}) {
    const char* name = wk.name;
    const std::string key = std::string("wall_contact.") + name;
    if (!r.vm.count(key)) continue;
    const LawBlock* block = wk.normal ? normal : tangential;
    const ParamSpec* spec = block ? block->find(name) : nullptr;
    if (!spec)
      throw ConfigError("key '" + key + "' needs a selected law with the parameter " + name +
                        " (contact.normal = " + c.normal_law + ", contact.tangential = " + c.tangential_law +
                        "); every key of a law's block can be given at walls in its pair block, [" +
                        wall_block_hint(block) + "]");
    w.*spec->target = r.get<double>(key);
    // The damping given replaces the disc-disc one: the other damping keys return to "not given".
    if (block->in_one_of(name))
      for (const char* other : block->one_of)
        if (std::string(other) != name) w.*block->find(other)->target = block->find(other)->def;
  }
  return w;
}

// True when a key of [bonds] or of a pair block [bonds.A.B] is given: the scene has bonds.
bool bonds_given(const LawCatalog& laws, const Reader& r) {
  if (!laws.bonds) return false;
  const std::string prefix = std::string(laws.bonds->section) + ".";
  for (const auto& [key, value] : r.vm)
    if (key.rfind(prefix, 0) == 0 && !value.defaulted()) return true;
  return false;
}

// [bonds] itself (not its pair blocks): given, every pair of discs is bonded with these parameters.
void read_bond_block(const LawCatalog& laws, const Reader& r, ContactParams& p) {
  const LawBlock& block = *laws.bonds;
  const std::string prefix = std::string(block.section) + ".";
  std::string given = r.given(prefix + "gap") ? prefix + "gap" : (r.given(prefix + "file") ? prefix + "file" : "");
  for (const ParamSpec& spec : block.params)
    if (given.empty() && r.given(prefix + spec.key)) given = prefix + spec.key;
  if (given.empty()) return;
  for (const ParamSpec& spec : block.params) {
    const std::string key = prefix + spec.key;
    if (!r.vm.count(key)) {
      r.required(key, " (required in [bonds], which '" + given +
                          "' turns on: every pair of discs is bonded; bond some pairs only with pair blocks "
                          "[bonds.A.B] and no [bonds])");
      continue;
    }
    p.*spec.target = law_param(r, key, spec);
  }
}

}  // namespace

void declare_law_param(KeyTable<Config>& table, const std::string& key, const ParamSpec& p, bool with_default,
                       const std::string& help) {
  const bool def = with_default && p.presence == Presence::defaulted;
  if (p.words.empty()) {
    table.declare_number<double>(key, def ? std::optional<double>(p.def) : std::nullopt, p.unit, p.range, help);
    return;
  }
  table.declare_choice(key, def ? std::optional<std::string>(p.text(p.def)) : std::nullopt,
                       std::vector<std::string>(p.words.begin(), p.words.end()), help);
}

double law_param(const Reader& r, const std::string& key, const ParamSpec& p) {
  if (p.words.empty()) return r.get<double>(key);  // in p.range: the validation pass checked it
  return p.word_index(r.get<std::string>(key));    // one of p.words: the validation pass checked it
}

void read_contact(const LawCatalog& laws, const Reader& r, Config& c) {
  refuse_unselected_blocks(laws, r, c);
  ContactParams p;
  for (const LawKind* kind : laws.kinds())
    if (const LawBlock* block = selected_block(laws, c, *kind))
      read_block(r, *kind, selected_keyword(laws, c, *kind), *block, p);
  c.bonds = bonds_given(laws, r);
  if (c.bonds) read_bond_block(laws, r, p);
  c.params = ContactParamTable(1);
  c.params.pair(0, 0) = p;
  c.params.wall(0) = read_wall_contact(laws, r, c, p);
}

bool unselected_law_block(const LawCatalog& laws, const Config& c, const std::string& section) {
  if (laws.bonds && section == laws.bonds->section) return !c.bonds;  // [bonds] only in a scene with bonds
  const LawKind* kind = block_kind(laws, section);
  if (!kind) return false;
  const LawBlock* block = selected_block(laws, c, *kind);
  return !block || section != block->section;
}

}  // namespace rondel::config
