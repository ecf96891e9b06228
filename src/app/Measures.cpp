#include "app/Measures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "app/RowGeometry.hpp"
#include "core/ExactSum.hpp"

namespace rondel {

std::string MeasuresRow::header() {
  return "step,time,width,height,wall_sxx,wall_syy,sxx,syy,sxy,s1,s3,eps_axial,eps_lateral,eps_vol,void_ratio,"
         "coordination,rotation_mean,rotation_std,sliding_fraction,rolling_yield_fraction,wall_tau,shear_disp,"
         "cell_lx,cell_ly,cell_tilt,shear_strain,kxx,kyy,kxy,pressure,tau,mu,inertial,phi";
}

std::string MeasuresRow::csv() const {
  std::ostringstream s;
  s.precision(12);
  s << step << ',';
  s.precision(16);
  s << time;
  s.precision(12);
  for (double v : {width,
                   height,
                   wall_sxx,
                   wall_syy,
                   sxx,
                   syy,
                   sxy,
                   s1,
                   s3,
                   eps_axial,
                   eps_lateral,
                   eps_vol,
                   void_ratio,
                   coordination,
                   rotation_mean,
                   rotation_std,
                   sliding_fraction,
                   rolling_yield_fraction,
                   wall_tau,
                   shear_disp,
                   cell_lx,
                   cell_ly,
                   cell_tilt,
                   shear_strain,
                   kxx,
                   kyy,
                   kxy,
                   pressure,
                   tau,
                   mu,
                   inertial,
                   phi})
    s << ',' << v;
  return s.str();
}

MeasuresRow Measures::row(std::int64_t step, double time, const DiscStore& discs, const ContactTable& pairs,
                          const ContactTable& wall_rows, const WallSet& walls, const BoxGeometry& box0,
                          const ContactSummary& contacts) const {
  MeasuresRow m;
  m.step = step;
  m.time = time;
  const BoxGeometry g = Boundaries::box(walls, domain_);
  m.width = g.width;
  m.height = g.height;
  box_stresses(m, walls, g);
  const double area = (g.has_x ? g.width : domain_.length_x()) * (g.has_y ? g.height : domain_.length_y());
  love_weber(m, discs, pairs, wall_rows, walls, area);
  m.eps_axial = box0.height > 0.0 ? (box0.height - g.height) / box0.height : 0.0;
  m.eps_lateral = box0.width > 0.0 ? (box0.width - g.width) / box0.width : 0.0;
  m.eps_vol = 1.0 - (g.width * g.height) / (box0.width * box0.height);
  disc_statistics(m, discs, area, contacts);
  cell_measures(m, discs, area);
  return m;
}

void Measures::cell_measures(MeasuresRow& m, const DiscStore& discs, double area) const {
  const Domain& d = domain_;
  m.cell_lx = d.length_x(), m.cell_ly = d.length_y(), m.cell_tilt = d.tilt;
  m.shear_strain = (d.tilt + static_cast<double>(flips_) * d.length_x()) / d.length_y();
  ExactSum xx, yy, xy, px, py, mass, solid, diameter;
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    const double mi = discs.mass[i];
    const Vec2 u = discs.velocity[i] - d.flow(discs.position[i]);
    xx += mi * u.x * u.x, yy += mi * u.y * u.y, xy += mi * u.x * u.y, px += mi * u.x, py += mi * u.y;
    mass += mi, solid += std::numbers::pi * discs.radius[i] * discs.radius[i], diameter += 2.0 * discs.radius[i];
  }
  // Apart from the mean flow's uniform part too: the discs' mean velocity relative to L (x - x0) is a free
  // translation (a wrap shifts a velocity, so the momentum drifts), not agitation. sum m (u - U)(u - U) =
  // sum m u u - M U U with M U = sum m u.
  const double scale = 1.0 / (area * thickness_), m_total = comm_.exact_sum(mass);
  const double qx = comm_.exact_sum(px), qy = comm_.exact_sum(py), inv_m = m_total > 0.0 ? 1.0 / m_total : 0.0;
  m.kxx = scale * (comm_.exact_sum(xx) - qx * qx * inv_m), m.kyy = scale * (comm_.exact_sum(yy) - qy * qy * inv_m);
  m.kxy = scale * (comm_.exact_sum(xy) - qx * qy * inv_m);
  m.pressure = 0.5 * (m.sxx + m.syy + m.kxx + m.kyy);
  m.tau = -(m.sxy + m.kxy);
  m.mu = m.pressure > 0.0 ? m.tau / m.pressure : 0.0;
  const double a_solid = comm_.exact_sum(solid);
  const double n = static_cast<double>(comm_.sum(static_cast<std::int64_t>(discs.n_owned())));
  const double rho = m_total / (a_solid * thickness_);
  const double d_mean = n > 0.0 ? comm_.exact_sum(diameter) / n : 0.0;
  m.inertial = m.pressure > 0.0 ? std::fabs(d.L.xy) * d_mean / std::sqrt(m.pressure / rho) : 0.0;
  m.phi = a_solid / area;
}

void Measures::box_stresses(MeasuresRow& m, const WallSet& walls, const BoxGeometry& g) const {
  double sx = 0.0, sy = 0.0;
  int nx = 0, ny = 0;
  for (const Wall& w : walls) {
    if (w.box_side == 1 || w.box_side == 2) sx += Boundaries::stress(w, g, thickness_), ++nx;
    if (w.box_side == 0 || w.box_side == 3) sy += Boundaries::stress(w, g, thickness_), ++ny;
  }
  m.wall_sxx = nx ? sx / nx : 0.0;
  m.wall_syy = ny ? sy / ny : 0.0;
  const Wall *bottom = nullptr, *top = nullptr;
  for (const Wall& w : walls) {
    if (w.box_side == 0) bottom = &w;
    if (w.box_side == 3) top = &w;
  }
  if (top) m.wall_tau = -top->force.x / (g.width * thickness_);
  if (top && bottom) m.shear_disp = top->p0.x - bottom->p0.x;
}

void Measures::love_weber(MeasuresRow& m, const DiscStore& discs, const ContactTable& pairs,
                          const ContactTable& wall_rows, const WallSet& walls, double area) const {
  // Booked rows only, so each contact counts once over all ranks.
  ExactSum xx, yy, xy, yx;
  const std::size_t n_owned = discs.n_owned();
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    if (static_cast<std::size_t>(pairs.i1[r]) >= n_owned || !(pairs.F_n[r] > 0.0)) continue;
    const Vec2 d = domain_.separation(discs.position[pairs.i1[r]], discs.position[pairs.i2[r]]);
    const Vec2 f = RowGeometry::pair_force(discs, domain_, pairs, static_cast<std::size_t>(r));
    xx += d.x * f.x, yy += d.y * f.y, xy += d.x * f.y, yx += d.y * f.x;
  }
  for (std::size_t r = 0; r < wall_rows.size(); ++r) {
    if (!(wall_rows.F_n[r] > 0.0)) continue;
    const ContactKinematics k =
        RowGeometry::wall(discs, walls[wall_rows.i2[r]], static_cast<std::size_t>(wall_rows.i1[r]));
    const Vec2 c = k.a1 * k.n, f = wall_rows.f1[r];
    xx += c.x * f.x, yy += c.y * f.y, xy += c.x * f.y, yx += c.y * f.x;
  }
  const double scale = -1.0 / (area * thickness_);
  m.sxx = scale * comm_.exact_sum(xx);
  m.syy = scale * comm_.exact_sum(yy);
  m.sxy = 0.5 * scale * (comm_.exact_sum(xy) + comm_.exact_sum(yx));
  const double centre = 0.5 * (m.sxx + m.syy);
  const double radius = std::sqrt(0.25 * (m.sxx - m.syy) * (m.sxx - m.syy) + m.sxy * m.sxy);
  m.s1 = centre + radius;
  m.s3 = centre - radius;
}

void Measures::disc_statistics(MeasuresRow& m, const DiscStore& discs, double area,
                               const ContactSummary& contacts) const {
  ExactSum solid, theta, theta2;
  std::int64_t n_free = 0;
  const std::size_t n_owned = discs.n_owned();
  for (std::size_t i = 0; i < n_owned; ++i) {
    solid += std::numbers::pi * discs.radius[i] * discs.radius[i];
    if (discs.flags[i] & kFlagFixed) continue;
    ++n_free;
    theta += discs.theta[i];
    theta2 += discs.theta[i] * discs.theta[i];
  }
  const double a_solid = comm_.exact_sum(solid);
  const double n = static_cast<double>(comm_.sum(static_cast<std::int64_t>(n_owned)));
  const double n_rot = std::max(1.0, static_cast<double>(comm_.sum(n_free)));
  m.void_ratio = (area - a_solid) / a_solid;
  m.rotation_mean = comm_.exact_sum(theta) / n_rot;
  m.rotation_std = std::sqrt(std::max(0.0, comm_.exact_sum(theta2) / n_rot - m.rotation_mean * m.rotation_mean));
  const double loaded = static_cast<double>(comm_.sum(contacts.contacts));
  m.coordination = 2.0 * static_cast<double>(comm_.sum(contacts.contacts - contacts.wall_contacts)) / n;
  m.sliding_fraction = loaded > 0 ? static_cast<double>(comm_.sum(contacts.sliding)) / loaded : 0.0;
  m.rolling_yield_fraction = loaded > 0 ? static_cast<double>(comm_.sum(contacts.rolling_yield)) / loaded : 0.0;
}

}  // namespace rondel
