#pragma once
// Internal to the configuration layer (Config*.cpp): reading the parsed keys with the checks and messages
// every section shares, and the readers of each section.
#include <boost/program_options.hpp>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
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
// Whitespace-separated numbers; ';'-separated records of them. Errors name `key`.
std::vector<double> numbers(const std::string& text, const std::string& key);
std::vector<std::vector<double>> records(const std::string& text, const std::string& key);

void read_contact(const LawCatalog& laws, const Reader& r, Config& c);
void read_walls(const Reader& r, Config& c);
// [material] or [material.NAME] (before the contact laws); then the wall materials and the pair blocks (after
// the laws and walls: the default parameters are copied to every pair, then the pair blocks override them).
void read_materials(const Reader& r, const DynamicSections& dynamic, Config& c);
void read_pairs(const LawCatalog& laws, const Reader& r, const DynamicSections& dynamic, Config& c);
// scene.materials and its fractions, scene.size_materials, walls.rough_materials (after read_scene).
void read_scene_materials(const Reader& r, Config& c);
void read_scene(const Reader& r, Config& c);
// Whether [section] is the block of a law that is not selected (left out of the resolved text).
bool unselected_law_block(const LawCatalog& laws, const Config& c, const std::string& section);

}  // namespace rondel::config
