#include "app/StartChecks.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/MemoryLimit.hpp"
#include "core/Partitioners.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel::start_checks {

namespace {

constexpr double kLightSpeed = 299792458.0;

bool normal_positive(double v) { return std::isfinite(v) && v >= DBL_MIN; }

std::string material_prefix(const Config& c, const Material& m) {
  return c.materials.size() > 1 || m.name != kDefaultMaterial ? "material." + m.name : std::string("material");
}

std::string radius_keys(const Config& c) { return c.scene.type->radius_keys(c.scene); }

std::string velocity_keys(const Config& c) {
  std::string keys = "scene.vx = " + fmt(c.scene.velocity.x) + ", scene.vy = " + fmt(c.scene.velocity.y) +
                     ", scene.omega = " + fmt(c.scene.omega);
  if (c.scene.type->source != SceneType::Source::keys)
    keys += " and the velocities of scene.file '" + c.scene.file + "'";
  return keys;
}

}  // namespace

std::string scene_keys(const Config& c) {
  return c.scene.type->placement_keys(c.scene) + "; domain.xlo, domain.xhi, domain.ylo, domain.yhi" +
         (c.walls.empty() ? "" : "; walls.box, walls.box_region, walls.lines, walls.segments");
}

std::string critical_keys(const Config& c) {
  std::ostringstream s;
  const LawCatalog& laws = law_catalog();
  const std::string selected[3] = {c.normal_law, c.tangential_law, c.rolling_law};
  const LawKind* kinds[3] = {&laws.normal, &laws.tangential, &laws.rolling};
  // Every parameter of the selected blocks: the defaults (disc-disc, then [wall_contact]'s disc-wall values
  // where they differ), then each pair block's values that differ from the defaults.
  const ContactParams &p = c.params.pair(0, 0), &w = c.params.wall(0, 0);
  const std::size_t n = c.materials.size();
  for (int k = 0; k < 3; ++k) {
    const LawInfo* law = kinds[k]->find(selected[k]);
    if (!law || !law->block) continue;
    const std::string block = law->block->section;
    for (const ParamSpec& spec : law->block->params) {
      if (p.*spec.target >= 0.0) s << block << "." << spec.key << " = " << fmt(p.*spec.target) << ", ";
      if (w.*spec.target >= 0.0 && w.*spec.target != p.*spec.target)
        s << "wall_contact." << spec.key << " = " << fmt(w.*spec.target) << ", ";
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b) {
          const double pair = c.params.pair(a, b).*spec.target, wall = c.params.wall(a, b).*spec.target;
          const std::string names = block + "." + c.materials[a].name + ".";
          if (b >= a && pair >= 0.0 && pair != p.*spec.target)
            s << names << c.materials[b].name << "." << spec.key << " = " << fmt(pair) << ", ";
          if (wall >= 0.0 && wall != w.*spec.target)
            s << names << "wall." << c.materials[b].name << "." << spec.key << " = " << fmt(wall) << ", ";
        }
    }
  }
  const LawInfo& normal = *laws.normal.find(c.normal_law);
  for (const Material& m : c.materials) {
    const std::string prefix = material_prefix(c, m);
    s << prefix << ".density = " << fmt(m.density) << ", " << prefix << ".thickness = " << fmt(m.thickness) << ", ";
    if (normal.elastic)
      s << prefix << ".youngs_modulus = " << fmt(m.youngs_modulus) << ", " << prefix
        << ".poisson_ratio = " << fmt(m.poisson_ratio) << ", ";
  }
  if (normal.stiffening) s << "run.max_overlap = " << fmt(c.max_overlap) << ", ";
  s << radius_keys(c);
  return s.str();
}

void check_masses(const Config& c, const std::vector<MaterialInfo>& materials) {
  for (std::size_t k = 0; k < materials.size() && k < c.materials.size(); ++k) {
    const MaterialInfo& info = materials[k];
    if (info.R_max <= 0.0) continue;  // no disc of this material
    const Material& m = c.materials[k];
    for (const double R : {info.R_min, info.R_max}) {
      const double mass = m.mass(R), inertia = m.inertia(mass, R);
      if (normal_positive(mass) && normal_positive(inertia)) continue;
      const std::string prefix = material_prefix(c, m);
      throw ConfigError("a disc of radius " + fmt(R) + " m has mass " + fmt(mass) + " kg and moment of inertia " +
                        fmt(inertia) + " kg m^2, not positive finite numbers a run can divide by: from " + prefix +
                        ".density = " + fmt(m.density) + ", " + prefix + ".thickness = " + fmt(m.thickness) + ", " +
                        prefix + ".body = " + body_name(m.body) + " and " + radius_keys(c));
    }
  }
}

// The keys of a "key = value, ..." list whose values lie far outside what double precision can combine
// (magnitude above 1e100 or below 1e-100): the ones that made a derived quantity overflow or vanish.
std::string extreme_keys(const std::string& list) {
  std::string out;
  std::size_t at = 0;
  while (at < list.size()) {
    std::size_t end = list.find(", ", at);
    if (end == std::string::npos) end = list.size();
    const std::string item = list.substr(at, end - at);
    const std::size_t eq = item.find(" = ");
    const double v = eq == std::string::npos ? 0.0 : std::strtod(item.c_str() + eq + 3, nullptr);
    if (v != 0.0 && (std::fabs(v) > 1e100 || std::fabs(v) < 1e-100)) out += (out.empty() ? "" : ", ") + item;
    at = end + 2;
  }
  return out;
}

void check_time_step(const Config& c, const CriticalStep& critical, double dt, double R_min) {
  if (!normal_positive(critical.dt)) {
    const std::string keys = critical_keys(c), culprits = extreme_keys(keys);
    throw ConfigError("the critical time step is " + fmt(critical.dt) + " s" +
                      (critical.mode.empty() ? std::string() : " (" + critical.mode + " mode, " + critical.pair + ")") +
                      ", not a positive finite step: " +
                      (culprits.empty() ? std::string("the stiffness, damping, density or radius is too large or too "
                                                      "small for double precision")
                                        : "made so by " + culprits +
                                              " (beyond 1e100 or below 1e-100: too large or too small for double "
                                              "precision; lower run.dt cannot help)") +
                      "; the keys that set it: " + keys);
  }
  if (!normal_positive(dt))
    throw ConfigError("the time step is " + fmt(dt) + " s (run.dt = " + fmt(c.dt) + ", run.safety = " + fmt(c.safety) +
                      " x the critical step " + fmt(critical.dt) + " s), not a positive finite step");
  if (!std::isfinite(dt * static_cast<double>(c.steps)))
    throw ConfigError("run.steps = " + std::to_string(c.steps) + " x the time step " + fmt(dt) +
                      " s is not a finite time: lower run.steps or run.dt");
  // A disc at rest falls g dt^2 / 2 in the first step: more than the overlap the run allows, and the first
  // contact (a wall, a disc below) already passes run.max_overlap. Ordinary runs are far below (1e-3 of it).
  const double fall = 0.5 * std::hypot(c.gravity.x, c.gravity.y) * dt * dt;
  if (fall > c.max_overlap * R_min)
    throw ConfigError("gravity.x = " + fmt(c.gravity.x) + ", gravity.y = " + fmt(c.gravity.y) +
                      " moves a disc at rest by " + fmt(fall) + " m in one time step of " + fmt(dt) +
                      " s, more than run.max_overlap = " + fmt(c.max_overlap) + " x the smallest radius " + fmt(R_min) +
                      " m: the contacts are too soft or the discs too heavy for the time step (run.dt = " + fmt(c.dt) +
                      ", run.safety = " + fmt(c.safety) + "); the keys that set the critical step " + fmt(critical.dt) +
                      " s: " + critical_keys(c));
}

void check_cells(const Config& c, double range) {
  // As CellGrid: floor(length / range) cells per side, at least 1, at most 1e5.
  auto per_side = [range](double length) { return std::clamp(std::floor(length / range), 1.0, 1.0e5); };
  const double cells = per_side(c.domain.length_x()) * per_side(c.domain.length_y());
  const double per_cell = Partitioners::bytes_per_cell(c.partitioner);
  check_memory(
      0.0, cells, per_cell,
      "the domain (domain.xlo, domain.xhi, domain.ylo, domain.yhi) in cells of side >= the interaction range " +
          fmt(range) + " m (2 x the largest radius + neighbour.skin; " + radius_keys(c) + ")");
}

void check_initial_motion(const Config& c, const DiscStore& discs) {
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    const Vec2 v = discs.velocity[i];
    const double speed = std::hypot(v.x, v.y) + std::fabs(discs.omega[i]) * discs.radius[i];
    const double ke =
        0.5 * discs.mass[i] * (v.x * v.x + v.y * v.y) + 0.5 * discs.inertia[i] * discs.omega[i] * discs.omega[i];
    if (std::isfinite(ke) && speed <= kLightSpeed) continue;
    throw ConfigError("disc " + std::to_string(discs.gid[i]) + " starts with speed |v| + |omega| R = " + fmt(speed) +
                      " m/s and kinetic energy " + fmt(ke) +
                      " J: a finite energy and a speed below the speed of light are allowed; from " + velocity_keys(c));
  }
}

void check_cell(const Config& c, const Domain& sizing, double range, double dt) {
  const Domain& d = c.domain;
  if (!c.cell_deforms()) return;
  const std::string step = " with run.dt = " + fmt(dt) + " s";
  if (!(std::fabs(d.vb.x) * dt < 0.5 * d.length_x()))
    throw ConfigError("cell.rate_xy = " + fmt(d.L.xy) + " 1/s" + step + " tilts the cell by " +
                      fmt(std::fabs(d.vb.x) * dt) + " m a step, not below half its width " + fmt(0.5 * d.length_x()) +
                      " m (at most one flip a step): lower the rate");
  const std::pair<const char*, double> rates[] = {{"cell.rate_xx", d.L.xx}, {"cell.rate_yy", d.L.yy}};
  for (const auto& [key, rate] : rates)
    if (!(std::fabs(rate) * dt < 0.5))
      throw ConfigError(std::string(key) + " = " + fmt(rate) + " 1/s" + step +
                        " changes the cell's length by half or more in one step: lower the rate");
  // A rate's length over the run is known (the sizing's); a stress target's is not: its length now must hold,
  // and a run that shrinks it below twice the range later stops there (Simulation::follow_cell).
  const auto check = [&](bool servo, const char* stress_key, const char* rate_key, double now, double smallest) {
    if (servo) {
      if (!(now >= 2.0 * range))
        throw ConfigError(std::string(stress_key) + ": the cell's length " + fmt(now) +
                          " m is below twice the interaction range " + fmt(range) +
                          " m (2 x largest radius + neighbour.skin): a larger cell");
    } else if (!(smallest >= 2.0 * range)) {
      throw ConfigError(std::string(rate_key) + ": over run.steps = " + std::to_string(c.steps) + step +
                        " the cell shrinks to a length of " + fmt(smallest) + " m, below twice the interaction range " +
                        fmt(range) +
                        " m (2 x largest radius + neighbour.skin): a larger cell, a lower rate or fewer "
                        "steps");
    }
  };
  check(c.cell_stress_xx > 0.0, "cell.stress_xx", "cell.rate_xx", d.length_x(), sizing.length_x());
  check(c.cell_stress_yy > 0.0, "cell.stress_yy", "cell.rate_yy", d.length_y(), sizing.length_y());
}

}  // namespace rondel::start_checks
