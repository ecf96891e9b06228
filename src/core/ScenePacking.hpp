#pragma once
// What the two random packings share (scene.type = random, ScenePacking.cpp, and random_tiles,
// ScenePackingTiles.cpp): their keys' checks, the keys named in messages, and the draw of a radius.
#include <cstddef>
#include <string>
#include <utility>

#include "core/Config.hpp"
#include "core/SceneBuilder.hpp"

namespace rondel::packing {

// scene.count, scene.sizes with scene.fractions, or scene.radius_min/_max (throws ConfigError naming the key).
void check_keys(SceneConfig& s);
std::string radius_keys(const SceneConfig& s);
std::string placement_keys(const SceneConfig& s);
// A radius, and its material: that of the slot (its own radius range when scene.material_radius_min is
// given), or of the size drawn (scene.size_materials). One number of `rng`.
std::pair<double, int> draw_radius(const SceneConfig& s, std::size_t slot, SceneRandom& rng);
// The largest radius the keys allow (scene.radius_max, the largest of scene.sizes or of scene.material_radius_max).
double largest_radius(const SceneConfig& s);
// The expected mean radius of scene.count discs drawn (each material's exact count with its own range).
double mean_radius(const SceneConfig& s);
// The smallest radius the keys allow.
double smallest_radius(const SceneConfig& s);
// Throws InputError when scene.region is narrower or lower than a disc of radius r_max.
void check_region(const SceneConfig& s, double r_max);

}  // namespace rondel::packing
