#include "Measures.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "Boundaries.hpp"
#include "Simulation.hpp"
#include "core/ExactSum.hpp"

namespace rondel {

std::string MeasuresRow::header() {
  return "step,time,width,height,wall_sxx,wall_syy,sxx,syy,sxy,s1,s3,eps_axial,eps_lateral,eps_vol,void_ratio,"
         "coordination,rotation_mean,rotation_std,sliding_fraction,rolling_yield_fraction,wall_tau,shear_disp";
}

std::string MeasuresRow::csv() const {
  std::ostringstream s;
  s.precision(12);
  s << step << ',';
  s.precision(16);
  s << time;
  s.precision(12);
  for (double v : {width, height, wall_sxx, wall_syy, sxx, syy, sxy, s1, s3, eps_axial, eps_lateral, eps_vol,
                   void_ratio, coordination, rotation_mean, rotation_std, sliding_fraction, rolling_yield_fraction, wall_tau,
                   shear_disp})
    s << ',' << v;
  return s.str();
}

// The run's reports on Simulation's state (collective): the global ledger, kinetic energies, the rows of
// diagnostics.csv and of measures.csv.

EnergyLedger Simulation::global_ledger() const {
  // Each rank integrates the work of the rows it books; the run's ledger is their sum (KE0 and the energy
  // scale are global already).
  EnergyLedger g = ledger_;
  g.for_each_term([this](const LedgerTermInfo& t, double& w) {
    if (!(t.uses & kTermRankShare)) return;
    ExactSum local;
    local += w;
    w = comm_.exact_sum(local);
  });
  return g;
}

void Simulation::kinetic_sums(ExactSum& trans, ExactSum& rot) const {
  // Of the free discs: fixed and glued discs move as their walls prescribe (their motion is boundary work).
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
    if (discs_.flags[i] & kFlagFixed) continue;
    trans += 0.5 * discs_.mass[i] * dot(discs_.velocity[i], discs_.velocity[i]);
    rot += 0.5 * discs_.inertia[i] * discs_.omega[i] * discs_.omega[i];
  }
}

double Simulation::kinetic_energy() const {
  ExactSum ke, rot;
  kinetic_sums(ke, rot);
  ke.merge(rot);
  return comm_.exact_sum(ke);
}

DiagnosticsRow Simulation::diagnostics() {
  DiagnosticsRow row;
  row.step = step_;
  row.time = time_;
  ExactSum ke_t, ke_r;
  kinetic_sums(ke_t, ke_r);
  row.ke_trans = comm_.exact_sum(ke_t);
  row.ke_rot = comm_.exact_sum(ke_r);
  std::int64_t contacts = 0, wall_contacts = 0;
  double worst = 0.0;
  for (std::size_t r = 0; r < pairs_.size(); ++r) {
    if (!(pairs_.F_n[r] > 0.0) || static_cast<std::size_t>(pairs_.i1[r]) >= discs_.n_owned()) continue;
    ++contacts;
    const auto i = static_cast<std::size_t>(pairs_.i1[r]), j = static_cast<std::size_t>(pairs_.i2[r]);
    const Vec2 d = config_.domain.separation(discs_.position[i], discs_.position[j]);
    const double u = discs_.radius[i] + discs_.radius[j] - std::sqrt(dot(d, d));
    worst = std::max(worst, u / std::min(discs_.radius[i], discs_.radius[j]));
  }
  for (std::size_t r = 0; r < wall_rows_.size(); ++r) {
    if (!(wall_rows_.F_n[r] > 0.0)) continue;
    ++wall_contacts;
    const auto i = static_cast<std::size_t>(wall_rows_.i1[r]);
    worst = std::max(worst, (discs_.radius[i] - walls_[wall_rows_.i2[r]].proximity(discs_.position[i]).dist) / discs_.radius[i]);
  }
  row.contacts = comm_.sum(contacts);
  row.wall_contacts = comm_.sum(wall_contacts);
  const std::int64_t n = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
  row.coordination = n > 0 ? 2.0 * row.contacts / n : 0.0;
  row.max_overlap = comm_.max(worst);
  EnergyLedger g = global_ledger();
  const ContactSummary stored =
      kernel_.stored(KernelContext{discs_, config_.domain, walls_, config_.params, dt_}, pairs_, wall_rows_);
  summary_ = stored;
  ExactSum stored_sum;
  stored_sum += stored.total();
  row.E_stored = comm_.exact_sum(stored_sum);
  row.imbalance = imbalance_;
  const double ghosts = comm_.sum(static_cast<double>(exchange_.ghost_count()));
  row.ghost_fraction = n > 0 ? ghosts / n : 0.0;
  row.migrated = comm_.sum(static_cast<std::int64_t>(migrated_));
  row.D_other = g.D_other(row.E_stored);
  row.residual = g.relative_residual(row.ke_trans + row.ke_rot);
  static_cast<LedgerTerms&>(row) = g;  // the run's ledger terms, scale updated
  ledger_.scale = g.scale;
  return row;
}

MeasuresRow Simulation::measures(const ContactSummary& contacts) {
  MeasuresRow m;
  m.step = step_;
  m.time = time_;
  boundaries_.measure(walls_, discs_, pairs_, wall_rows_, comm_);
  const BoxGeometry g = Boundaries::box(walls_, config_.domain);
  m.width = g.width;
  m.height = g.height;
  double sx = 0.0, sy = 0.0;
  int nx = 0, ny = 0;
  for (const Wall& w : walls_) {
    if (w.box_side == 1 || w.box_side == 2) sx += Boundaries::stress(w, g, config_.thickness), ++nx;
    if (w.box_side == 0 || w.box_side == 3) sy += Boundaries::stress(w, g, config_.thickness), ++ny;
  }
  m.wall_sxx = nx ? sx / nx : 0.0;
  m.wall_syy = ny ? sy / ny : 0.0;
  const Wall *bottom = nullptr, *top = nullptr;
  for (const Wall& w : walls_) {
    if (w.box_side == 0) bottom = &w;
    if (w.box_side == 3) top = &w;
  }
  if (top) m.wall_tau = -top->force.x / (g.width * config_.thickness);
  if (top && bottom) m.shear_disp = top->p0.x - bottom->p0.x;

  // Love-Weber: booked rows only, so each contact counts once over all ranks.
  ExactSum xx, yy, xy, yx;
  const std::size_t n_owned = discs_.n_owned();
  for (std::size_t r = 0; r < pairs_.size(); ++r) {
    if (static_cast<std::size_t>(pairs_.i1[r]) >= n_owned || !(pairs_.F_n[r] > 0.0)) continue;
    const Vec2 d = config_.domain.separation(discs_.position[pairs_.i1[r]], discs_.position[pairs_.i2[r]]);
    const Vec2 f = pairs_.f1[r];
    xx += d.x * f.x, yy += d.y * f.y, xy += d.x * f.y, yx += d.y * f.x;
  }
  for (std::size_t r = 0; r < wall_rows_.size(); ++r) {
    if (!(wall_rows_.F_n[r] > 0.0)) continue;
    const auto i = static_cast<std::size_t>(wall_rows_.i1[r]);
    const Wall::Proximity prox = walls_[wall_rows_.i2[r]].proximity(discs_.position[i]);
    const double a1 = discs_.radius[i] - 0.5 * (discs_.radius[i] - prox.dist);
    const Vec2 c = a1 * prox.n, f = wall_rows_.f1[r];
    xx += c.x * f.x, yy += c.y * f.y, xy += c.x * f.y, yx += c.y * f.x;
  }
  const double area = (g.has_x ? g.width : config_.domain.length_x()) * (g.has_y ? g.height : config_.domain.length_y());
  const double scale = -1.0 / (area * config_.thickness);
  m.sxx = scale * comm_.exact_sum(xx);
  m.syy = scale * comm_.exact_sum(yy);
  m.sxy = 0.5 * scale * (comm_.exact_sum(xy) + comm_.exact_sum(yx));
  const double centre = 0.5 * (m.sxx + m.syy);
  const double radius = std::sqrt(0.25 * (m.sxx - m.syy) * (m.sxx - m.syy) + m.sxy * m.sxy);
  m.s1 = centre + radius;
  m.s3 = centre - radius;

  m.eps_axial = box0_.height > 0.0 ? (box0_.height - g.height) / box0_.height : 0.0;
  m.eps_lateral = box0_.width > 0.0 ? (box0_.width - g.width) / box0_.width : 0.0;
  m.eps_vol = 1.0 - (g.width * g.height) / (box0_.width * box0_.height);

  ExactSum solid, theta, theta2;
  std::int64_t n_free = 0;
  for (std::size_t i = 0; i < n_owned; ++i) {
    solid += std::numbers::pi * discs_.radius[i] * discs_.radius[i];
    if (discs_.flags[i] & kFlagFixed) continue;
    ++n_free;
    theta += discs_.theta[i];
    theta2 += discs_.theta[i] * discs_.theta[i];
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
  return m;
}

}  // namespace rondel
