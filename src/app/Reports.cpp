// The run's reports on a Simulation's state (collective): the global ledger, kinetic energies, the rows of
// diagnostics.csv, the stability check and the bit-exact state text.
#include "app/Reports.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "app/RowGeometry.hpp"
#include "core/Errors.hpp"
#include "core/ExactSum.hpp"
#include "core/Format.hpp"
#include "parallel/ByteBuffer.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/OrderedText.hpp"

namespace rondel {

Reports::Reports(const RunState& state)
    : state_(state),
      comm_(state.comm),
      discs_(state.discs),
      pairs_(state.pairs),
      wall_rows_(state.wall_rows),
      walls_(state.walls),
      ledger_(state.ledger) {}

EnergyLedger Reports::global_ledger() const {
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

void Reports::kinetic_sums(ExactSum& trans, ExactSum& rot) const {
  // Of the free discs: fixed and glued discs move as their walls prescribe (their motion is boundary work).
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
    if (discs_.flags[i] & kFlagFixed) continue;
    trans += 0.5 * discs_.mass[i] * dot(discs_.velocity[i], discs_.velocity[i]);
    rot += 0.5 * discs_.inertia[i] * discs_.omega[i] * discs_.omega[i];
  }
}

double Reports::kinetic_energy() const {
  ExactSum ke, rot;
  kinetic_sums(ke, rot);
  ke.merge(rot);
  return comm_.exact_sum(ke);
}

DiagnosticsRow Reports::diagnostics(const ContactSummary& stored, double& scale) const {
  DiagnosticsRow row;
  row.step = state_.step;
  row.time = state_.time;
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
    const double u = RowGeometry::pair(discs_, state_.config.domain, i, j).u_n;
    worst = std::max(worst, u / std::min(discs_.radius[i], discs_.radius[j]));
  }
  for (std::size_t r = 0; r < wall_rows_.size(); ++r) {
    if (!(wall_rows_.F_n[r] > 0.0)) continue;
    ++wall_contacts;
    const auto i = static_cast<std::size_t>(wall_rows_.i1[r]);
    worst = std::max(worst, RowGeometry::wall(discs_, walls_[wall_rows_.i2[r]], i).u_n / discs_.radius[i]);
  }
  row.contacts = comm_.sum(contacts);
  row.wall_contacts = comm_.sum(wall_contacts);
  const std::int64_t n = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
  row.coordination = n > 0 ? 2.0 * row.contacts / n : 0.0;
  row.max_overlap = comm_.max(worst);
  EnergyLedger g = global_ledger();
  ExactSum stored_sum;
  stored_sum += stored.total();
  row.E_stored = comm_.exact_sum(stored_sum);
  row.imbalance = state_.imbalance;
  const double ghosts = comm_.sum(static_cast<double>(state_.ghosts));
  row.ghost_fraction = n > 0 ? ghosts / n : 0.0;
  row.migrated = comm_.sum(static_cast<std::int64_t>(state_.migrated));
  row.bonds = comm_.sum(stored.bonds);
  row.D_other = g.D_other(row.E_stored);
  row.residual = g.relative_residual(row.ke_trans + row.ke_rot);
  static_cast<LedgerTerms&>(row) = g;  // the run's ledger terms, scale updated
  scale = g.scale;
  return row;
}

std::string Reports::most_energetic_disc() const {
  double best = -1.0;
  std::int64_t gid = -1;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
    const double ke = 0.5 * discs_.mass[i] * dot(discs_.velocity[i], discs_.velocity[i]) +
                      0.5 * discs_.inertia[i] * discs_.omega[i] * discs_.omega[i];
    if (ke > best || std::isnan(ke)) best = std::isnan(ke) ? INFINITY : ke, gid = discs_.gid[i];
  }
  const double top = comm_.max(best);
  const std::int64_t who = comm_.max(best == top ? gid : std::int64_t{-1});
  return std::to_string(who) + " (kinetic energy " + fmt(top) + " J)";
}

void Reports::check_stability(const DiagnosticsRow& row, double& d_other_peak) const {
  if (!std::isfinite(row.ke_trans + row.ke_rot))
    throw InstabilityError("step " + std::to_string(row.step) + ": the kinetic energy is not finite");
  if (row.residual > state_.config.max_residual)
    throw InstabilityError(
        "step " + std::to_string(row.step) + ": the energy ledger residual reached " + fmt(row.residual) +
        " of the energy scale (run.max_residual = " + fmt(state_.config.max_residual) +
        "): energy grows with no work done, the integration is unstable; the most energetic disc is " +
        most_energetic_disc() + "; lower run.dt or run.safety");
  // D_other = -E_stored(0) + the dissipation of the dashpots (and the integration error): for closed
  // spring-dashpots it only grows. A fall below its peak is energy the contacts created, the sign of a step
  // the ledger itself cannot catch (its books close whatever the step).
  d_other_peak = std::max(d_other_peak, row.D_other);
  const double gain = d_other_peak - row.D_other, scale = std::max(row.scale, row.E_stored);
  if (scale > 0.0 && gain > state_.config.max_energy_gain * scale)
    throw InstabilityError("step " + std::to_string(row.step) + ": the contacts created " + fmt(gain) +
                           " J of energy (D_other fell from " + fmt(d_other_peak) + " to " + fmt(row.D_other) +
                           " J: " + fmt(gain / scale, 3) +
                           " of the energy scale; run.max_energy_gain = " + fmt(state_.config.max_energy_gain) +
                           "): a closed spring-dashpot cannot do positive work, so the time step is too large for "
                           "the contacts; the most energetic disc is " +
                           most_energetic_disc() + "; lower run.dt, or leave run.force_dt off");
}

namespace {

// One line of final.csv: the radius is the last column, so the first seven stay as they were (scripts and
// comparisons that read them). %.17g reads back to the same double, as %a does.
struct FinalRecord {
  std::int64_t gid;
  double x, y, vx, vy, theta, omega, radius;
};
constexpr const char* kFinalHeader = "gid,x,y,vx,vy,theta,omega,radius\n";

FinalRecord final_record(const DiscStore& d, std::size_t i) {
  return {d.gid[i],        d.position[i].x, d.position[i].y, d.velocity[i].x,
          d.velocity[i].y, d.theta[i],      d.omega[i],      d.radius[i]};
}

void append_final_line(const FinalRecord& d, bool decimal, std::string& out) {
  char buf[512];
  const auto gid = static_cast<long long>(d.gid);
  if (decimal)
    std::snprintf(buf, sizeof buf, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", gid, d.x, d.y, d.vx, d.vy,
                  d.theta, d.omega, d.radius);
  else
    std::snprintf(buf, sizeof buf, "%lld,%a,%a,%a,%a,%a,%a,%a\n", gid, d.x, d.y, d.vx, d.vy, d.theta, d.omega,
                  d.radius);
  out += buf;
}

}  // namespace

std::string Reports::state_text() const {
  ByteBuffer mine;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) mine.put(final_record(discs_, i));
  const auto all = comm_.gather(mine);
  if (!comm_.root()) return "";
  std::vector<FinalRecord> records;
  for (const ByteBuffer& b : all) {
    ByteReader r(b.bytes.data(), b.bytes.size());
    while (!r.done()) records.push_back(r.get<FinalRecord>());
  }
  std::sort(records.begin(), records.end(), [](const auto& a, const auto& b) { return a.gid < b.gid; });
  std::string out = kFinalHeader;
  const bool decimal = state_.config.final_format == FinalFormat::decimal;
  for (const FinalRecord& d : records) append_final_line(d, decimal, out);
  return out;
}

void Reports::write_final(const std::string& path) const {
  CanonicalOrder order;
  order.arrange(
      discs_.n_owned(),
      [&](std::size_t i) {
        return OrderKey{discs_.gid[i], 0};
      },
      sizeof(FinalRecord),
      [&](std::size_t i, char* out) {
        const FinalRecord r = final_record(discs_, i);
        std::memcpy(out, &r, sizeof r);
      },
      comm_);
  const bool decimal = state_.config.final_format == FinalFormat::decimal;
  write_ordered_text(
      path, kFinalHeader, order,
      [&](std::size_t k, std::string& out) {
        FinalRecord r{};
        if (order.is_local(k))
          r = final_record(discs_, order.local_index(k));
        else
          std::memcpy(&r, order.received(k), sizeof r);
        append_final_line(r, decimal, out);
      },
      comm_);
}

}  // namespace rondel
