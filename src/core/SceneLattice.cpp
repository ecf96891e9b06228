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

std::vector<SceneDisc> lattice(const SceneInputs& in, bool hex) {
  const SceneConfig& s = in.scene;
  const Domain& domain = in.domain;
  check_memory(static_cast<double>(s.nx) * s.ny, 0.0, 0.0, "scene.nx x scene.ny");
  std::vector<SceneDisc> out;
  const double row = hex ? s.spacing * std::sqrt(3.0) / 2.0 : s.spacing;
  // The corners of the lattice (the first disc, the farthest row and column, the half shift of hex rows).
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
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const double shift = (hex && (j % 2 == 1)) ? 0.5 * s.spacing : 0.0;
      out.push_back({static_cast<std::int64_t>(out.size()),
                     {s.x0 + i * s.spacing + shift, s.y0 + j * row},
                     s.radius,
                     s.velocity,
                     s.omega});
    }
  const auto slots = scene::material_slots(s, out.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k].material = scene::slot_material(s, slots[k]);
  return out;
}

std::vector<SceneDisc> square(const SceneInputs& in) { return lattice(in, false); }
std::vector<SceneDisc> hexagonal(const SceneInputs& in) { return lattice(in, true); }

}  // namespace

extern const SceneType kLatticeSquareScene{"lattice_square",
                                           "scene.nx x scene.ny discs on a square lattice",
                                           check_lattice,
                                           lattice_keys,
                                           lattice_radius,
                                           SceneType::Source::keys,
                                           false,
                                           square};
extern const SceneType kLatticeHexScene{"lattice_hex",  "scene.nx x scene.ny discs on a hexagonal lattice",
                                        check_lattice,  lattice_keys,
                                        lattice_radius, SceneType::Source::keys,
                                        false,          hexagonal};

}  // namespace rondel
