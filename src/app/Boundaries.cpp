#include "app/Boundaries.hpp"

#include <algorithm>
#include <cmath>

#include "app/RowGeometry.hpp"
#include "core/ExactSum.hpp"

namespace rondel {

namespace {
const Wall* side(const WallSet& walls, int s) {
  for (const Wall& w : walls)
    if (w.box_side == s) return &w;
  return nullptr;
}
}  // namespace

bool Boundaries::controlled(const WallSet& walls) {
  return std::any_of(walls.begin(), walls.end(),
                     [](const Wall& w) { return w.control != Wall::Control::velocity || w.shear_velocity != 0.0; });
}

bool Boundaries::any_rough(const WallSet& walls) {
  return std::any_of(walls.begin(), walls.end(), [](const Wall& w) { return w.rough; });
}

WallLoads Boundaries::local_loads(const WallSet& walls, const DiscStore& discs, const Domain& domain,
                                  const ContactTable& pairs, const ContactTable& wall_rows) {
  const std::size_t n_owned = discs.n_owned();
  WallLoads loads;
  loads.sums.resize(walls.size());
  loads.counts.assign(walls.size(), 0);
  auto& sums = loads.sums;
  auto& counts = loads.counts;
  if (any_rough(walls)) {
    for (std::size_t r = 0; r < pairs.size(); ++r) {
      if (static_cast<std::size_t>(pairs.i1[r]) >= n_owned || !(pairs.F_n[r] > 0.0)) continue;
      const std::uint32_t a = discs.flags[pairs.i1[r]], b = discs.flags[pairs.i2[r]];
      if (is_attached(a) == is_attached(b)) continue;  // free-free, or two glued discs (of different walls)
      const std::size_t w = attached_wall(is_attached(a) ? a : b);
      const Vec2 f1 = RowGeometry::pair_force(discs, domain, pairs, r);
      const Vec2 on_wall = is_attached(a) ? f1 : -f1;
      sums[w][0] += on_wall.x;
      sums[w][1] += on_wall.y;
      sums[w][2] += -dot(on_wall, walls[w].normal);
      ++counts[w];
    }
  }
  for (std::size_t r = 0; r < wall_rows.size(); ++r) {
    if (static_cast<std::size_t>(wall_rows.i1[r]) >= n_owned || !(wall_rows.F_n[r] > 0.0)) continue;
    const auto w = static_cast<std::size_t>(wall_rows.i2[r]);
    const Vec2 on_wall = -wall_rows.f1[r];
    sums[w][0] += on_wall.x;
    sums[w][1] += on_wall.y;
    sums[w][2] += wall_rows.F_n[r];
    ++counts[w];
  }
  return loads;
}

std::vector<std::array<std::size_t, 4>> WallLoads::add_to(FusedReduction& r) const {
  std::vector<std::array<std::size_t, 4>> slots(sums.size());
  for (std::size_t w = 0; w < sums.size(); ++w)
    slots[w] = {r.sum(sums[w][0]), r.sum(sums[w][1]), r.sum(sums[w][2]), r.sum(counts[w])};
  return slots;
}

void Boundaries::apply(WallSet& walls, const FusedReduction& r, const std::vector<std::array<std::size_t, 4>>& slots) {
  for (std::size_t w = 0; w < walls.size(); ++w) {
    walls[w].force = {r.sum_exact(slots[w][0]).value(), r.sum_exact(slots[w][1]).value()};
    walls[w].normal_force = r.sum_exact(slots[w][2]).value();
    walls[w].contacts = r.sum_int(slots[w][3]);
  }
}

void Boundaries::measure(WallSet& walls, const DiscStore& discs, const Domain& domain, const ContactTable& pairs,
                         const ContactTable& wall_rows, const Communicator& comm) const {
  FusedReduction r;
  const auto slots = local_loads(walls, discs, domain, pairs, wall_rows).add_to(r);
  r.reduce(comm);
  apply(walls, r, slots);
}

void Boundaries::glue(DiscStore& discs, const WallSet& walls, double depth) {
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    for (std::size_t w = 0; w < walls.size(); ++w) {
      if (!walls[w].rough || !(walls[w].proximity(discs.position[i]).dist < depth)) continue;
      discs.flags[i] = attached_flags(w);
      discs.velocity[i] = walls[w].velocity;
      discs.omega[i] = 0.0;
      break;
    }
  }
}

void Boundaries::move_glued(DiscStore& discs, const WallSet& walls, const Domain& domain, double dt) {
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    if (!is_attached(discs.flags[i])) continue;
    const Vec2 v = walls[attached_wall(discs.flags[i])].velocity;
    discs.velocity[i] = v;
    discs.position[i] += dt * v;
    domain.wrap(discs.position[i]);
  }
}

double Boundaries::move_walls(WallSet& walls, DiscStore& discs, const Domain& domain, double thickness,
                              double dt) const {
  if (controlled_) steer(walls, domain, thickness, dt);
  for (auto& w : walls) w.move(dt);
  if (!rough_) return 0.0;
  move_glued(discs, walls, domain, dt);
  double v_wall = 0.0;
  for (const Wall& w : walls) v_wall = std::max(v_wall, std::sqrt(dot(w.velocity, w.velocity)));
  return v_wall * dt;
}

double Boundaries::glued_work_half(const DiscStore& discs, double dt) {
  double W = 0.0;
  for (std::size_t i = 0; i < discs.n_owned(); ++i)
    if (is_attached(discs.flags[i])) W -= 0.5 * dot(discs.force[i], discs.velocity[i]) * dt;
  return W;
}

std::vector<std::int64_t> Boundaries::glued_counts(const DiscStore& discs, std::size_t n_walls) {
  std::vector<std::int64_t> glued(n_walls + 1, 0);
  for (std::size_t i = 0; i < discs.n_owned(); ++i)
    if (is_attached(discs.flags[i])) ++glued[std::min(attached_wall(discs.flags[i]), n_walls)];
  return glued;
}

BoxGeometry Boundaries::box(const WallSet& walls, const Domain& domain) {
  BoxGeometry g;
  const Wall *bottom = side(walls, 0), *left = side(walls, 1), *right = side(walls, 2), *top = side(walls, 3);
  g.has_x = left && right;
  g.has_y = bottom && top;
  g.width = (right ? right->p0.x : domain.xhi) - (left ? left->p0.x : domain.xlo);
  g.height = (top ? top->p0.y : domain.yhi) - (bottom ? bottom->p0.y : domain.ylo);
  return g;
}

double Boundaries::stress(const Wall& w, const BoxGeometry& g, double thickness) {
  if (w.box_side < 0) return 0.0;
  const double length = (w.box_side == 1 || w.box_side == 2) ? g.height : g.width;
  return w.normal_force / (length * thickness);
}

void Boundaries::steer(WallSet& walls, const Domain& domain, double thickness, double dt) const {
  const BoxGeometry g = box(walls, domain);
  for (Wall& w : walls) {
    if (w.control == Wall::Control::velocity) {
      if (w.shear_velocity != 0.0) w.velocity = w.shear_velocity * w.tangent();
      continue;
    }
    double v_n = 0.0;
    const bool vertical = w.box_side == 1 || w.box_side == 2;
    if (w.control == Wall::Control::strain_rate) {
      v_n = w.strain_rate * (vertical ? g.width : g.height);
    } else {
      const double length = vertical ? g.height : g.width;
      const double error = w.target_stress * length * thickness - w.normal_force;
      v_n = gain_ * error / (static_cast<double>(std::max<std::int64_t>(w.contacts, 1)) * (k_n_ * dt + c_n_));
      v_n = std::clamp(v_n, -v_max_, v_max_);
    }
    w.velocity = v_n * w.normal + w.shear_velocity * w.tangent();
  }
}

}  // namespace rondel
