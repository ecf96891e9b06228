// scene.type = lattice_square | lattice_hex: scene.nx x scene.ny discs of scene.radius, the first at
// (scene.x0, scene.y0), centres scene.spacing apart (0: touching); hex rows shifted by half a spacing, sqrt(3)/2
// spacings apart. Numbered row by row, by x within a row.
#include <cmath>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/MemoryLimit.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace {

void check_lattice(SceneConfig& s) {
  config::check(s.nx > 0, "scene.nx", "must be > 0 for a lattice", std::to_string(s.nx));
  config::check(s.ny > 0, "scene.ny", "must be > 0 for a lattice", std::to_string(s.ny));
  config::check(s.radius > 0.0, "scene.radius", "must be > 0 for a lattice", config::num(s.radius));
  if (s.spacing == 0.0) s.spacing = 2.0 * s.radius;
  scene::check_numbering_placement(s);
}

std::string lattice_keys(const SceneConfig&) {
  return "scene.nx, scene.ny, scene.radius, scene.spacing, scene.x0, scene.y0";
}
std::string lattice_radius(const SceneConfig& s) { return "scene.radius = " + fmt(s.radius); }

// The lattice's extent checked against the domain (its corners, the farthest row and column, the half shift of hex
// rows); throws InputError naming the keys.
void check_extent(const SceneInputs& in, bool hex) {
  const SceneConfig& s = in.scene;
  const Domain& domain = in.domain;
  const double row = hex ? s.spacing * std::sqrt(3.0) / 2.0 : s.spacing;
  const double far_x = s.x0 + (s.nx - 1) * s.spacing + (hex && s.ny > 1 ? 0.5 * s.spacing : 0.0),
               far_y = s.y0 + (s.ny - 1) * row;
  const bool inside_x = domain.periodic_x || (s.x0 >= domain.xlo && far_x <= domain.xhi);
  const bool inside_y = domain.periodic_y || (s.y0 >= domain.ylo && far_y <= domain.yhi);
  if (!std::isfinite(far_x) || !std::isfinite(far_y) || !inside_x || !inside_y) {
    std::ostringstream m;
    m << "keys 'scene.nx', 'scene.ny', 'scene.spacing' (" << s.spacing << "; 0: 2 x scene.radius), 'scene.x0', "
      << "'scene.y0': the lattice spans (" << s.x0 << ", " << s.y0 << ") to (" << far_x << ", " << far_y
      << "), outside the domain (domain.xlo, domain.xhi, domain.ylo, domain.yhi) [" << domain.xlo << ", " << domain.xhi
      << "] x [" << domain.ylo << ", " << domain.yhi << "]";
    throw InputError(m.str());
  }
}

// The site of gid k (row k / nx, column k % nx).
SceneDisc site(const SceneConfig& s, bool hex, std::int64_t k) {
  const double row = hex ? s.spacing * std::sqrt(3.0) / 2.0 : s.spacing;
  const auto j = static_cast<int>(k / s.nx), i = static_cast<int>(k % s.nx);
  const double shift = (hex && (j % 2 == 1)) ? 0.5 * s.spacing : 0.0;
  return {k, {s.x0 + i * s.spacing + shift, s.y0 + j * row}, s.radius, s.velocity, s.omega};
}

std::int64_t sites(const SceneConfig& s) { return static_cast<std::int64_t>(s.nx) * s.ny; }

// The sites [first, first + count), each with its material slot from the keyed shuffle of the whole lattice's exact
// counts (scene::material_slot_of: no list of every site).
std::vector<SceneDisc> lattice_block(const SceneInputs& in, bool hex, std::int64_t first, std::int64_t count) {
  const SceneConfig& s = in.scene;
  check_memory(static_cast<double>(count), 0.0, 0.0, "scene.nx x scene.ny");
  check_extent(in, hex);
  const auto n = static_cast<std::uint64_t>(sites(s));
  const std::vector<std::size_t> counts = scene::material_counts(s, n);
  std::vector<SceneDisc> out;
  out.reserve(static_cast<std::size_t>(count));
  for (std::int64_t k = first; k < first + count; ++k) {
    out.push_back(site(s, hex, k));
    out.back().material = scene::slot_material(s, scene::material_slot_of(s, counts, n, static_cast<std::uint64_t>(k)));
  }
  return out;
}

std::vector<SceneDisc> lattice(const SceneInputs& in, bool hex) { return lattice_block(in, hex, 0, sites(in.scene)); }

std::vector<SceneDisc> square(const SceneInputs& in) { return lattice(in, false); }
std::vector<SceneDisc> hexagonal(const SceneInputs& in) { return lattice(in, true); }
std::vector<SceneDisc> square_block(const SceneInputs& in, std::int64_t first, std::int64_t count) {
  return lattice_block(in, false, first, count);
}
std::vector<SceneDisc> hexagonal_block(const SceneInputs& in, std::int64_t first, std::int64_t count) {
  return lattice_block(in, true, first, count);
}

}  // namespace

extern const SceneType kLatticeSquareScene{"lattice_square",
                                           "scene.nx x scene.ny discs on a square lattice",
                                           check_lattice,
                                           lattice_keys,
                                           lattice_radius,
                                           SceneType::Source::keys,
                                           false,
                                           square,
                                           sites,
                                           square_block};
extern const SceneType kLatticeHexScene{"lattice_hex",  "scene.nx x scene.ny discs on a hexagonal lattice",
                                        check_lattice,  lattice_keys,
                                        lattice_radius, SceneType::Source::keys,
                                        false,          hexagonal,
                                        sites,          hexagonal_block};

}  // namespace rondel
