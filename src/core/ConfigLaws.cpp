// [contact], the law blocks and [wall_contact]. Which laws exist, their keywords, blocks and parameters
// come from the law catalog (physics/LawRegistry); only the linear law's "at most one of zeta, c_n, e"
// rule and the [wall_contact] block are written out here.
#include <string>

#include "core/ConfigRead.hpp"

namespace rondel::config {

namespace {

// The Config field that holds the keyword selected for `kind`.
std::string Config::*keyword_field(const LawKind& kind) {
  const std::string name = kind.kind;
  return name == "normal" ? &Config::normal_law : name == "tangential" ? &Config::tangential_law : &Config::rolling_law;
}
const std::string& selected_keyword(const Config& c, const LawKind& kind) { return c.*keyword_field(kind); }
const LawBlock* selected_block(const Config& c, const LawKind& kind) {
  const LawInfo* law = kind.find(selected_keyword(c, kind));
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
    const LawBlock* block = selected_block(c, *kind);
    if (!block || section != block->section)
      throw ConfigError("key '" + key + "' belongs to the [" + section + "] block, but that law is not selected (" +
                        "contact." + kind->kind + " = " + selected_keyword(c, *kind) + ")");
  }
}

// Every parameter of the selected law's block, in declaration order, into p.
void read_block(const Reader& r, const LawKind& kind, const std::string& law, const LawBlock& block, ContactParams& p) {
  for (const ParamSpec& spec : block.params) {
    const std::string key = std::string(block.section) + "." + spec.key;
    if (!r.vm.count(key)) {
      if (spec.presence == Presence::required)
        r.required(key, " (required with contact." + std::string(kind.kind) + " = " + law + ")");
      continue;
    }
    const double v = r.get<double>(key);
    in_range(v, spec.range, key);
    p.*spec.target = v;
  }
}

void read_linear_rule(const Reader& r) {
  int damping_keys = 0;
  for (const char* k : {"linear.zeta", "linear.c_n", "linear.e"}) damping_keys += r.vm.count(k) ? 1 : 0;
  if (damping_keys > 1) throw ConfigError("keys 'linear.zeta', 'linear.c_n', 'linear.e': give at most one");
}

// [wall_contact]: the disc-disc parameters p with the keys given here replacing theirs.
ContactParams read_wall_contact(const Reader& r, const Config& c, const ContactParams& p) {
  ContactParams w = p;
  w.rolling = r.get<bool>("wall_contact.rolling");
  if (r.vm.count("wall_contact.k_n")) positive(r, "wall_contact.k_n"), w.k_n = r.get<double>("wall_contact.k_n");
  if (r.vm.count("wall_contact.zeta") && r.vm.count("wall_contact.e"))
    throw ConfigError("keys 'wall_contact.zeta' and 'wall_contact.e': give at most one");
  if (r.vm.count("wall_contact.zeta"))
    non_negative(w.zeta_n = r.get<double>("wall_contact.zeta"), "wall_contact.zeta"), w.c_n_fixed = -1.0, w.e_n = -1.0;
  if (r.vm.count("wall_contact.e")) {
    const double e = r.get<double>("wall_contact.e");
    in_range(e, kRestitution, "wall_contact.e");
    w.e_n = e;
    w.c_n_fixed = -1.0;
  }
  for (const char* k : {"wall_contact.k_n", "wall_contact.zeta"})
    if (r.vm.count(k) && c.normal_law != "linear")
      throw ConfigError(std::string("key '") + k + "' needs contact.normal = linear (hertz: the materials' E and nu, " +
                        "[hertz.A.wall.W] e)");
  if (r.vm.count("wall_contact.k_s") && c.tangential_law != "coulomb")
    throw ConfigError("key 'wall_contact.k_s' needs contact.tangential = coulomb");
  if (r.vm.count("wall_contact.mu") && c.tangential_law == "none")
    throw ConfigError("key 'wall_contact.mu' needs contact.tangential = coulomb or mindlin");
  if (r.vm.count("wall_contact.k_s")) positive(r, "wall_contact.k_s"), w.k_s = r.get<double>("wall_contact.k_s");
  if (r.vm.count("wall_contact.mu")) non_negative(w.mu = r.get<double>("wall_contact.mu"), "wall_contact.mu");
  return w;
}

}  // namespace

void read_contact(const LawCatalog& laws, const Reader& r, Config& c) {
  for (const LawKind* kind : laws.kinds()) {
    const std::string key = std::string("contact.") + kind->kind;
    std::string& keyword = c.*keyword_field(*kind);
    keyword = r.get<std::string>(key);
    check(kind->find(keyword) != nullptr, key, kind->keywords(), keyword);
  }
  refuse_unselected_blocks(laws, r, c);
  ContactParams p;
  for (const LawKind* kind : laws.kinds()) {
    const std::string& keyword = selected_keyword(c, *kind);
    if (kind == &laws.normal && keyword == "linear") read_linear_rule(r);
    if (const LawBlock* block = selected_block(c, *kind)) read_block(r, *kind, keyword, *block, p);
  }
  c.params = ContactParamTable(1);
  c.params.pair(0, 0) = p;
  c.params.wall(0) = read_wall_contact(r, c, p);
}

bool unselected_law_block(const LawCatalog& laws, const Config& c, const std::string& section) {
  const LawKind* kind = block_kind(laws, section);
  if (!kind) return false;
  const LawBlock* block = selected_block(c, *kind);
  return !block || section != block->section;
}

}  // namespace rondel::config
