#pragma once
// Internal to the configuration layer (Config*.cpp): reading the parsed keys with the checks and messages
// every section shares, and the readers of each section.
#include <boost/program_options.hpp>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "core/Config.hpp"
#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
#include "core/KeyTable.hpp"
#include "core/LawSpec.hpp"

namespace rondel::config {

struct Reader {
  const boost::program_options::variables_map& vm;
  template <class T>
  T get(const std::string& key) const {
    return vm[key].as<T>();
  }
  bool given(const std::string& key) const { return vm.count(key) && !vm[key].defaulted(); }
  double required(const std::string& key, const std::string& why) const {
    if (!vm.count(key)) throw ConfigError("missing required key '" + key + "'" + why);
    return vm[key].as<double>();
  }
};

// Throws "key 'K' = GOT is not allowed: ALLOWED" unless ok.
void check(bool ok, const std::string& key, const std::string& allowed, const std::string& got);
std::string num(double v);  // 10 significant digits, for messages
void positive(const Reader& r, const std::string& key);
void non_negative(double v, const std::string& key);
void in_range(double v, const Range& range, const std::string& key);  // "must be " + range.text()

// Any finite number; a speed (of a disc, a wall) below the speed of light; |gravity| up to 1e12 m/s^2 (about a
// neutron star's surface: anything larger is taken for a mistake).
inline constexpr Range kFinite{-INFINITY, INFINITY, false, false};
inline constexpr double kLightSpeed = 299792458.0;
inline constexpr Range kSpeed{-kLightSpeed, kLightSpeed, false, false};
inline constexpr Range kGravity{-1e12, 1e12, false, false};

// The keys of every section whose name is fixed (ConfigSchema.cpp), and of the dynamic sections
// (ConfigMaterials.cpp; with `help`, once with the placeholders).
// `readers` (when given) receives the reader of every row that fills a field of Config.
void declare_fixed_keys(const LawCatalog& laws, boost::program_options::options_description& all,
                        std::vector<KeySpec>& keys, std::vector<KeyReader<Config>>* readers = nullptr);
// The keys of [material] (`named` false) or [material.NAME] (prefix "material.NAME"), filling a Material.
void declare_material_keys(boost::program_options::options_description& d, std::vector<KeySpec>& keys,
                           const std::string& prefix, bool named, std::vector<KeyReader<Material>>* readers = nullptr);
void declare_dynamic_keys(const LawCatalog& laws, const DynamicSections& dynamic, bool help,
                          boost::program_options::options_description& all, std::vector<KeySpec>& keys);

// The validation pass: every value given (not the defaults) is finite and in its declared range, every
// number of a list too. Throws ConfigError naming the key, the value and what is allowed.
void validate_values(const std::vector<KeySpec>& keys, const boost::program_options::variables_map& vm);
// A flag given with an empty value ("run.overwrite =" or "--run.overwrite="), which Boost reads as true.
void refuse_empty_flags(const std::vector<KeySpec>& keys, const std::vector<std::string>& args,
                        const std::string& ini_text);

// The rules across keys, after the rows have filled their fields (Config.cpp calls them in this order).
// [run], [output]: what the ranges cannot say (a name for run.output, the snapshot's positions).
void read_run(const Reader& r, Config& c);
// [material] or [material.NAME] (before the contact laws); then the wall materials and the pair blocks (after
// the laws and walls: the default parameters are copied to every pair, then the pair blocks override them).
void read_materials(const Reader& r, const DynamicSections& dynamic, Config& c);
void read_contact(const LawCatalog& laws, const Reader& r, Config& c);
// Config::walls from Config::wall_keys.
void read_walls(Config& c);
void read_pairs(const LawCatalog& laws, const Reader& r, const DynamicSections& dynamic, Config& c);
// scene.region's default and the scene type's own rules; then scene.materials and its fractions,
// scene.size_materials, walls.rough_materials.
void read_scene(Config& c);
void read_scene_materials(Config& c);
// A law parameter's key: a number in its range, or one of its words (ParamSpec::words); `with_default`: its
// default applies (a block's key; a pair block's keys have none). `help`: its help line.
void declare_law_param(KeyTable<Config>& table, const std::string& key, const ParamSpec& p, bool with_default,
                       const std::string& help);
// A law parameter's value as given: its number, or its word's index (the validation pass checked either).
double law_param(const Reader& r, const std::string& key, const ParamSpec& p);
// Whether [section] is the block of a law that is not selected, or [bonds] in a scene without bonds (left out of the
// resolved text).
bool unselected_law_block(const LawCatalog& laws, const Config& c, const std::string& section);

}  // namespace rondel::config
