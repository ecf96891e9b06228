#include "core/WallLine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/ConfigRead.hpp"

namespace rondel {

Wall WallLine::read(const std::vector<double>& rec, const Domain& d) {
  config::check(rec.size() == 4 || rec.size() == 6 || rec.size() == 7, key,
                "'px py nx ny', 'px py nx ny vx vy' or 'px py nx ny omega cx cy' per wall",
                "a record of " + std::to_string(rec.size()) + " numbers");
  Wall w;
  w.kind = kind;
  w.p0 = {rec[0], rec[1]};
  const double len = std::hypot(rec[2], rec[3]);
  config::check(len > 0.0, key, "a non-zero normal", "normal (0, 0)");
  w.normal = {rec[2] / len, rec[3] / len};
  read_wall_motion(rec, 4, key, w);
  if (w.rotates()) {  // the points of the line that discs can meet lie in the domain
    for (Vec2 corner : {Vec2{d.xlo, d.ylo}, Vec2{d.xhi, d.ylo}, Vec2{d.xlo, d.yhi}, Vec2{d.xhi, d.yhi}})
      w.lever = std::max(w.lever, std::hypot(corner.x - w.centre.x, corner.y - w.centre.y));
  }
  return w;
}

std::string WallLine::behind(const Wall& w, double dist) {
  if (dist >= 0.0) return "";
  return std::string("its centre is on the far side of the line; the wall is from ") +
         (w.box_side >= 0 ? "walls.box and walls.box_region" : key);
}

namespace {

// Clips the line p + t d to the box: [lo, hi] of t (lo > hi when it misses the box).
void clip_to_box(Vec2 p, Vec2 d, const Domain& box, double& lo, double& hi) {
  const double p_[2] = {p.x, p.y}, d_[2] = {d.x, d.y}, a[2] = {box.xlo, box.ylo}, b[2] = {box.xhi, box.yhi};
  for (int k = 0; k < 2; ++k) {
    if (d_[k] == 0.0) {
      if (p_[k] < a[k] || p_[k] > b[k]) lo = 1.0, hi = 0.0;
      continue;
    }
    const double t1 = (a[k] - p_[k]) / d_[k], t2 = (b[k] - p_[k]) / d_[k];
    lo = std::max(lo, std::min(t1, t2));
    hi = std::min(hi, std::max(t1, t2));
  }
}

}  // namespace

void WallLine::outline(const Wall& w, const WallSet& walls, const Domain& domain, std::vector<Vec2>& out) {
  const double inf = std::numeric_limits<double>::infinity();
  const Vec2 d{-w.normal.y, w.normal.x};
  double lo = -inf, hi = inf;
  clip_to_box(w.p0, d, domain, lo, hi);
  if (lo > hi) {  // outside the domain: a piece as long as the box's diagonal, nearest its centre
    const double half = 0.5 * std::hypot(domain.length_x(), domain.length_y());
    const Vec2 c{0.5 * (domain.xlo + domain.xhi), 0.5 * (domain.ylo + domain.yhi)};
    lo = dot(c - w.p0, d) - half, hi = lo + 2.0 * half;
  }
  // The discs' side of every other line: (p0 + t d - q) . m >= 0.
  double a = lo, b = hi;
  for (const Wall& o : walls) {
    const double slope = dot(d, o.normal), offset = dot(w.p0 - o.p0, o.normal);
    if (&o == &w || o.kind != kind || std::abs(slope) < 1e-12) continue;
    if (slope > 0.0)
      a = std::max(a, -offset / slope);
    else
      b = std::min(b, -offset / slope);
  }
  if (a < b) lo = a, hi = b;  // else the other lines leave nothing: the box's piece is drawn
  out.push_back(w.p0 + lo * d), out.push_back(w.p0 + hi * d);
}

}  // namespace rondel
