// [material] or [material.NAME], the materials of walls, and the pair blocks [BLOCK.A.B] / [BLOCK.A.wall.W]
// that override the run's default law parameters for one unordered pair of materials (docs/physics.md
// section 7). Their section names are chosen by the user, so the schema learns them from the keys given
// (dynamic_sections) before the parse.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/ConfigSchema.hpp"

namespace rondel {

namespace po = boost::program_options;

namespace {

std::vector<std::string> split_dots(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t dot; (dot = s.find('.', start)) != std::string::npos; start = dot + 1)
    out.push_back(s.substr(start, dot - start));
  out.push_back(s.substr(start));
  return out;
}

const LawBlock* find_block(const LawCatalog& laws, const std::string& section) {
  for (const LawBlock* b : laws.blocks())
    if (section == b->section) return b;
  return nullptr;
}

// The words of the dynamic section names: [material.NAME], and the disc-wall pair [BLOCK.A.wall.W].
constexpr const char* kMaterialSection = "material";
constexpr const char* kWallPart = "wall";
// The key of a pair block [contact.A.B] that is not a law block: rolling resistance on or off for the pair.
constexpr const char* kContactSection = "contact";

void add_pair_keys(po::options_description& d, std::vector<KeySpec>& keys, const LawCatalog& laws,
                   const std::string& section) {
  const std::string block = section.substr(0, section.find('.'));
  config::KeyTable<Config> table(d, keys);
  if (block == kContactSection) {
    table.declare_flag(section + ".rolling", std::nullopt,
                       "false: no rolling resistance at this pair (rolling = none here)");
    return;
  }
  for (const ParamSpec& p : find_block(laws, block)->params)
    declare_law_param(table, section + "." + p.key, p, false, p.help);
}

}  // namespace

std::vector<std::string> ini_keys(const std::string& ini_text) {
  std::vector<std::string> out;
  std::istringstream in(ini_text);
  std::string section, line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#' || line[first] == ';') continue;
    line = line.substr(first);
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    std::string key = line.substr(0, eq);
    key.erase(key.find_last_not_of(" \t") + 1);
    out.push_back(section.empty() ? key : section + "." + key);
  }
  return out;
}

std::vector<std::string> argument_keys(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const std::string& a : args)
    if (a.rfind("--", 0) == 0) out.push_back(a.substr(2, a.find('=') - 2));
  return out;
}

DynamicSections dynamic_sections(const LawCatalog& laws, const std::vector<std::string>& full_keys) {
  std::set<std::string> materials, pairs;
  for (const std::string& key : full_keys) {
    const auto parts = split_dots(key);
    if (parts.size() == 3 && parts[0] == kMaterialSection) materials.insert(parts[1]);
    const bool block = parts[0] == kContactSection || find_block(laws, parts[0]);
    if (block && parts.size() == 4) pairs.insert(parts[0] + "." + parts[1] + "." + parts[2]);
    if (block && parts.size() == 5 && parts[2] == kWallPart)
      pairs.insert(parts[0] + "." + parts[1] + ".wall." + parts[3]);
  }
  return {{materials.begin(), materials.end()}, {pairs.begin(), pairs.end()}};
}

po::options_description config_schema(const LawCatalog& laws, const DynamicSections& dynamic, bool help) {
  po::options_description all;
  std::vector<KeySpec> keys;
  config::declare_fixed_keys(laws, all, keys);
  config::declare_dynamic_keys(laws, dynamic, help, all, keys);
  return all;
}

namespace config {

void declare_material_keys(po::options_description& d, std::vector<KeySpec>& keys, const std::string& prefix,
                           bool named, std::vector<KeyReader<Material>>* readers) {
  static constexpr Choice<Material::Body> kBodies[] = {
      {kBodyNames[0].name, kBodyNames[0].body, "m = rho pi R^2 t, I = m R^2/2"},
      {kBodyNames[1].name, kBodyNames[1].body, "m = 4/3 pi rho R^3, I = 2/5 m R^2"}};
  const std::string p = prefix + ".";
  KeyTable<Material> table(d, keys, readers);
  if (named)
    table.number_without_default(p + "density", at(&Material::density), "kg/m^3", kPositive, "density", true,
                                 " (every material has a density)");
  else
    table.number(p + "density", at(&Material::density), 2650.0, "kg/m^3", kPositive, "density");
  table.number(p + "thickness", at(&Material::thickness), 1.0, "m", kPositive,
               "disc thickness t (forces and energies are per t; the same for every material)");
  table.choice(p + "body", at(&Material::body), "disc", kBodies, "the body of the discs");
  table.number_without_default(p + "youngs_modulus", at(&Material::youngs_modulus), "Pa", kPositive,
                               "Young's modulus E (with an elastic normal law: contact.normal = hertz)", false);
  table.number_without_default(p + "poisson_ratio", at(&Material::poisson_ratio), "-", Range{-1.0, 0.5, true, true},
                               "Poisson's ratio nu (with an elastic normal law: contact.normal = hertz)", false);
}

void declare_dynamic_keys(const LawCatalog& laws, const DynamicSections& dynamic, bool help,
                          po::options_description& all, std::vector<KeySpec>& keys) {
  if (help) {
    po::options_description m(
        "[material.NAME] one material of several (instead of [material]; NAME: letters, "
        "digits, _; materials are numbered in name order)");
    declare_material_keys(m, keys, "material.NAME", true);
    po::options_description p(
        "[BLOCK.A.B] disc-disc and [BLOCK.A.wall.W] disc-wall parameters of one unordered material pair: any key "
        "of the selected law's block BLOCK, replacing the default (e.g. [linear.glass.steel] k_n = 2e6); "
        "[contact.A.B] and [contact.A.wall.W] hold the key below");
    add_pair_keys(p, keys, laws, "contact.A.B");
    all.add(m).add(p);
    return;
  }
  for (const std::string& name : dynamic.materials) {
    po::options_description m("[material." + name + "]");
    declare_material_keys(m, keys, "material." + name, true);
    all.add(m);
  }
  for (const std::string& section : dynamic.pairs) {
    po::options_description p("[" + section + "]");
    add_pair_keys(p, keys, laws, section);
    all.add(p);
  }
}

}  // namespace config

namespace config {

namespace {

Material read_material(const po::variables_map& vm, const std::string& prefix, const std::string& name, bool named) {
  po::options_description unused;
  std::vector<KeySpec> keys;
  std::vector<KeyReader<Material>> readers;
  declare_material_keys(unused, keys, prefix, named, &readers);
  Material m;
  m.name = name;
  for (const auto& read : readers) read(vm, m);
  return m;
}

// A law that needs the materials' elastic constants (hertz, mindlin: LawInfo::elastic) needs E and nu of every
// material; a law that needs a certain normal law (mindlin: hertz's beta) has it.
void check_law_needs(const LawCatalog& laws, const Reader& r, const Config& c, bool named) {
  const std::string selected[] = {c.normal_law, c.tangential_law, c.rolling_law};
  const auto kinds = laws.kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const LawInfo* law = kinds[k]->find(selected[k]);
    if (law->needs_normal && c.normal_law != law->needs_normal)
      throw ConfigError("key 'contact." + std::string(kinds[k]->kind) + "' = " + law->keyword +
                        " needs contact.normal = " + law->needs_normal + " (" + law->needs_why + ")");
    if (!law->elastic) continue;
    for (const Material& m : c.materials) {
      const std::string prefix = named ? "material." + m.name : std::string("material");
      for (const char* key : {".youngs_modulus", ".poisson_ratio"})
        if (!r.vm.count(prefix + key))
          throw ConfigError("missing required key '" + prefix + key + "' (contact." + kinds[k]->kind + " = " +
                            law->keyword + ")");
    }
  }
}

int material_named(const Config& c, const std::string& name, const std::string& key) {
  const int i = material_index(c.materials, name);
  if (i >= 0) return i;
  std::string known;
  for (const Material& m : c.materials) known += (known.empty() ? "" : ", ") + m.name;
  throw ConfigError((key[0] == '[' ? "section " + key : "key '" + key + "'") + " names the material '" + name +
                    "', which is not defined (materials: " + known + ")");
}

// walls.material (every wall) and walls.materials ('side:NAME ...', box walls).
void read_wall_materials(Config& c) {
  const std::string& all = c.wall_keys.material;
  const int base = all.empty() ? 0 : material_named(c, all, "walls.material");
  for (Wall& w : c.walls) w.material = base;
  for (const std::string& spec : c.wall_keys.materials) {
    const auto colon = spec.find(':');
    if (colon == std::string::npos) throw ConfigError("key 'walls.materials': '" + spec + "' is not 'side:NAME'");
    const std::string side = spec.substr(0, colon);
    bool found = false;
    for (Wall& w : c.walls)
      if (w.box_side >= 0 && w.box_side == box_side_index(side))
        w.material = material_named(c, spec.substr(colon + 1), "walls.materials"), found = true;
    if (!found) throw ConfigError("key 'walls.materials': '" + side + "' is not a side listed in walls.box");
  }
}

// The parameters of `section` ("BLOCK.A.B" or "BLOCK.A.wall.W") given in the INI or on the command line.
// A pair block [bonds.A.B] without [bonds] bonds its pair alone: it gives every required key itself.
void require_bond_keys(const LawBlock& block, const std::string& section, const ContactParams& p) {
  for (const ParamSpec& spec : block.params)
    if (spec.presence == Presence::required && !(p.*spec.target > 0.0))
      throw ConfigError("missing required key '" + section + "." + spec.key + "' (without [bonds], a pair block [" +
                        section + "] bonds its pair alone and gives " + "every required key of [bonds])");
}

void read_pair_block(const LawCatalog& laws, const Reader& r, const std::string& section, ContactParams& p) {
  const std::string block = section.substr(0, section.find('.'));
  if (block == kContactSection) {
    if (r.vm.count(section + ".rolling")) p.rolling = r.get<bool>(section + ".rolling");
    return;
  }
  const LawBlock& law = *find_block(laws, block);
  int one_of = 0;
  for (const ParamSpec& spec : law.params) {
    const std::string key = section + "." + spec.key;
    if (!r.vm.count(key)) continue;
    p.*spec.target = law_param(r, key, spec);
    if (!law.in_one_of(spec.key)) continue;
    ++one_of;  // the key given replaces the default's: the others of its group return to "not given"
    for (const char* other : law.one_of)
      if (std::string(other) != spec.key) p.*law.find(other)->target = law.find(other)->def;
  }
  if (one_of > 1) {
    std::string keys;
    for (const char* k : law.one_of) keys += (keys.empty() ? "" : ", ") + std::string(k);
    throw ConfigError("section [" + section + "]: give at most one of " + keys);
  }
}

}  // namespace

void read_materials(const Reader& r, const DynamicSections& dynamic, Config& c) {
  const bool named = !dynamic.materials.empty();
  if (named) {
    for (const char* k : {"material.density", "material.thickness", "material.body", "material.youngs_modulus",
                          "material.poisson_ratio"})
      if (r.given(k))
        throw ConfigError(std::string("key '") + k +
                          "': give either the single [material] section or [material.NAME] sections, not both");
    for (const std::string& name : dynamic.materials) {
      const bool ok = !name.empty() && name != kWallPart && std::all_of(name.begin(), name.end(), [](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
      });
      if (!ok)
        throw ConfigError("section [material." + name + "]: a material name is letters, digits and _ (not 'wall')");
      c.materials.push_back(read_material(r.vm, "material." + name, name, true));
    }
  } else {
    c.materials.push_back(read_material(r.vm, "material", kDefaultMaterial, false));
  }
  for (const Material& m : c.materials)
    if (m.thickness != c.materials.front().thickness)
      throw ConfigError("key 'material." + m.name + ".thickness' = " + num(m.thickness) +
                        ": every material has the thickness of the first (material." + c.materials.front().name +
                        ".thickness = " + num(c.materials.front().thickness) + "), the thickness the stresses are per");
  c.thickness = c.materials.front().thickness;
}

void read_pairs(const LawCatalog& laws, const Reader& r, const DynamicSections& dynamic, Config& c) {
  check_law_needs(laws, r, c, !dynamic.materials.empty());
  read_wall_materials(c);
  const std::size_t n = c.materials.size();
  const ContactParams disc = c.params.pair(0, 0), wall = c.params.wall(0);
  c.params = ContactParamTable(n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) c.params.pair(a, b) = disc, c.params.wall(a, b) = wall;
  std::set<std::string> seen;  // "BLOCK|a|b|wall" of every block read, to refuse a pair given both ways
  for (const std::string& section : dynamic.pairs) {
    const auto parts = split_dots(section);
    const bool at_wall = parts.size() == 4;
    const std::string first = "[" + section + "]";
    const auto a = static_cast<std::size_t>(material_named(c, parts[1], first));
    const auto b = static_cast<std::size_t>(material_named(c, parts[at_wall ? 3 : 2], first));
    const std::string id = parts[0] + "|" + std::to_string(std::min(a, b)) + "|" + std::to_string(std::max(a, b));
    if (!at_wall && !seen.insert(id).second)
      throw ConfigError("section [" + section + "]: the pair is given twice (a pair is unordered: [" + parts[0] + "." +
                        parts[2] + "." + parts[1] + "] is the same)");
    const bool bonds = laws.bonds && parts[0] == laws.bonds->section;
    if (bonds && at_wall)
      throw ConfigError("section [" + section +
                        "]: bonds join discs, not a disc and a wall (a disc glued to a wall: "
                        "walls.rough)");
    if (at_wall) {
      read_pair_block(laws, r, section, c.params.wall(a, b));
    } else {
      read_pair_block(laws, r, section, c.params.pair(a, b));
      if (bonds) require_bond_keys(*laws.bonds, section, c.params.pair(a, b));
      c.params.pair(b, a) = c.params.pair(a, b);
    }
  }
}

}  // namespace config

}  // namespace rondel
