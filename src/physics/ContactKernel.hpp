#pragma once
// The fused contact kernel: one pass over the contact rows, templated on the selected (normal,
// tangential, rolling) laws so that a `none` law compiles to nothing (docs/design.md section 3). Every row is
// evaluated in its canonical frame from the discs' positions and half-step velocities; its forces go to
// the row's columns and are summed per disc afterwards (ForceAssembly), in ascending partner gid.
//
// Energy ledger (docs/physics.md section 5): the work of each contact on the relative motion is integrated
// with the half-step velocities and the trapezoid of last and this step's force,
//   dW_n = (F_n' + F_n)/2 v_n dt,  dW_t = (F_t' + F_t)/2 V_s dt,  dW_r = sum_i (M_i' + M_i)/2 omega_i dt,
// and a moving wall's work on a disc is (f' + f)/2 . v_wall dt. The laws report Coulomb slip, rolling
// plastic and dashpot work and brittle-break releases. A row is booked by the rank that owns its disc 1,
// so a border pair computed on two ranks counts once.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/LedgerTerms.hpp"
#include "core/Wall.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawConcepts.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

// This step's ledger terms: the kernel books those of kTermKernel (the rest stay zero).
struct LedgerStep : LedgerTerms {
  // The worst overlap above the context's limit this step (u_n / smaller radius; 0 when none), and where.
  double worst_overlap = 0.0;
  ContactKey worst_key;
  bool worst_at_wall = false;
};

// The contacts now: energy held by their springs [J per thickness], how many carry load, how many slide
// (|F_t| at mu F_n) and how many have yielded in rolling (|M| at the law's cap). Booked rows only.
struct ContactSummary {
  double normal = 0.0, tangential = 0.0, rolling = 0.0;
  std::int64_t contacts = 0, wall_contacts = 0, sliding = 0, rolling_yield = 0;
  double total() const { return normal + tangential + rolling; }
};

struct KernelContext {
  const DiscStore& discs;
  const Domain& domain;
  const WallSet& walls;
  const ContactParamTable& params;
  double dt;
  double overlap_limit = INFINITY;  // report overlaps above this fraction of the smaller radius
};

template <class Normal, class Tangential, class Rolling>
struct ContactKernel {
  static constexpr std::size_t kTSlots = Tangential::slots.size();
  static constexpr std::size_t kRSlots = Rolling::slots.size();

  static void run(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows, LedgerStep& ledger) {
    run_rows<false>(c, pairs, ledger);
    run_rows<true>(c, wall_rows, ledger);
  }

  // The forces of the initial state for the first half kick (c.dt = 0): the laws see a copy of each
  // row's history, so a capping rule that resets a spring (a dashpot alone above the cap) commits
  // nothing, and no work is booked. The run starts from the history it was given.
  static void initial_forces(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows) {
    LedgerStep unused;
    run_rows<false, false>(c, pairs, unused);
    run_rows<true, false>(c, wall_rows, unused);
  }

  static ContactSummary stored_energy(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows) {
    ContactSummary e;
    stored_rows<false>(c, pairs, e);
    stored_rows<true>(c, wall_rows, e);
    return e;
  }

 private:
  struct Slots {
    std::array<double*, kTSlots + 1> t{};
    std::array<double*, kRSlots + 1> r{};
    explicit Slots(ContactTable& tab) {
      for (std::size_t s = 0; s < kTSlots; ++s) t[s] = tab.slot[s].data();
      for (std::size_t s = 0; s < kRSlots; ++s) r[s] = tab.slot[kTSlots + s].data();
    }
  };

  // The history the laws of row r write to: the table's columns (committed), or a copy of the row's
  // values that is dropped afterwards (scratch; the laws then index row 0 of the copy).
  struct CommittedHistory {
    const Slots& h;
    std::size_t row;
    CommittedHistory(const Slots& slots, std::size_t r) : h(slots), row(r) {}
    double* const* t() const { return h.t.data(); }
    double* const* r() const { return h.r.data(); }
  };
  struct ScratchHistory {
    std::array<double, kTSlots + 1> tv{};
    std::array<double, kRSlots + 1> rv{};
    std::array<double*, kTSlots + 1> tp{};
    std::array<double*, kRSlots + 1> rp{};
    std::size_t row = 0;
    ScratchHistory(const Slots& slots, std::size_t r) {
      for (std::size_t s = 0; s < kTSlots; ++s) tv[s] = slots.t[s][r], tp[s] = &tv[s];
      for (std::size_t s = 0; s < kRSlots; ++s) rv[s] = slots.r[s][r], rp[s] = &rv[s];
    }
    ScratchHistory(const ScratchHistory&) = delete;  // tp and rp point into this object
    double* const* t() const { return tp.data(); }
    double* const* r() const { return rp.data(); }
  };
  template <bool kCommit>
  using History = std::conditional_t<kCommit, CommittedHistory, ScratchHistory>;

  struct Row {
    ContactKinematics k;
    ContactBodies b;
    double w1 = 0.0, w2 = 0.0;
    Vec2 v_wall;
    bool coincident = false;
  };

  // Kinematics of row r; false when the discs are apart and the row carries no force (nothing to do).
  template <bool kWall>
  static bool kinematics(const KernelContext& c, const ContactTable& tab, std::size_t r, Row& row) {
    const DiscStore& D = c.discs;
    row.coincident = false;
    const auto i = static_cast<std::size_t>(tab.i1[r]);
    const auto j = static_cast<std::size_t>(tab.i2[r]);
    const bool loaded = tab.F_n[r] != 0.0 || tab.F_t[r] != 0.0;
    row.w1 = D.omega[i];
    if constexpr (kWall) {
      const Wall& w = c.walls[j];
      const Wall::Proximity prox = w.proximity(D.position[i]);
      if (prox.dist >= D.radius[i] && !loaded) return false;
      row.v_wall = w.velocity;
      row.k = disc_wall_kinematics(prox.n, prox.dist, D.radius[i], D.velocity[i], w.velocity, row.w1);
      row.b = disc_wall_bodies(D.mass[i], D.inertia[i]);
    } else {
      const Vec2 d = c.domain.separation(D.position[i], D.position[j]);
      const double dist2 = dot(d, d);
      const double Rs = D.radius[i] + D.radius[j];
      if (dist2 >= Rs * Rs && !loaded) return false;
      if (dist2 == 0.0) return !(row.coincident = true);  // no normal exists: reported as a failed run
      row.w2 = D.omega[j];
      row.k = disc_disc_kinematics(d, std::sqrt(dist2), D.radius[i], D.radius[j], D.velocity[i], D.velocity[j], row.w1,
                                   row.w2);
      row.b = disc_disc_bodies(D.mass[i], D.mass[j], D.inertia[i], D.inertia[j]);
    }
    return true;
  }

  template <bool kCommit>
  static void open_row(ContactTable& tab, std::size_t r, const Slots& h) {
    if constexpr (kCommit) {
      for (std::size_t s = 0; s < kTSlots; ++s) h.t[s][r] = 0.0;
      for (std::size_t s = 0; s < kRSlots; ++s) h.r[s][r] = 0.0;
    }
    tab.F_n[r] = 0.0;
    tab.F_t[r] = 0.0;
    if constexpr (Rolling::kActive) {
      tab.M1[r] = 0.0;
      tab.M2[r] = 0.0;
    }
    tab.f1[r] = {};
    tab.tq1[r] = 0.0;
    tab.tq2[r] = 0.0;
  }

  // The worst overlap above the context's limit (u_n / smaller radius), and where.
  template <bool kWall>
  [[gnu::always_inline]] static void note_overlap(const KernelContext& c, const ContactKinematics& k,
                                                  const ContactKey& key, LedgerStep& L) {
    const double R_small = kWall ? k.R1 : std::min(k.R1, k.R2);
    if (k.u_n > c.overlap_limit * R_small && k.u_n > L.worst_overlap * R_small) {
      L.worst_overlap = k.u_n / R_small;
      L.worst_key = key;
      L.worst_at_wall = kWall;
    }
  }

  // The ledger's share of a booked row: the trapezoid of last and this step's force and couples, and the
  // laws' dissipation.
  template <bool kWall>
  [[gnu::always_inline]] static void book_work(const ContactTable& tab, std::size_t r, const Row& row, double F_n,
                                               const TangentialForce& T, const RollingCouple& M, Vec2 f1, double dt,
                                               LedgerStep& L) {
    const ContactKinematics& k = row.k;
    L.W_n += 0.5 * (tab.F_n[r] + F_n) * k.v_n * dt;
    L.W_t += 0.5 * (tab.F_t[r] + T.F_t) * k.V_s * dt;
    L.D_slip += T.slip;
    if constexpr (Rolling::kActive) {
      L.W_r += 0.5 * ((tab.M1[r] + M.M1) * row.w1 + (tab.M2[r] + M.M2) * row.w2) * dt;
      L.D_r_plastic += M.plastic;
      L.D_r_dashpot += M.dashpot;
      L.E_r_break += M.released;
    }
    if constexpr (kWall) L.W_w += 0.5 * dot(tab.f1[r] + f1, row.v_wall) * dt;
  }

  // This step's result into the row's columns (the per-disc sums read f1, tq1, tq2).
  template <bool kWall>
  [[gnu::always_inline]] static void store_row(ContactTable& tab, std::size_t r, const ContactKinematics& k, double F_n,
                                               const TangentialForce& T, const RollingCouple& M, Vec2 f1) {
    tab.F_n[r] = F_n;
    tab.F_t[r] = T.F_t;
    if constexpr (Rolling::kActive) {
      tab.M1[r] = M.M1;
      tab.M2[r] = M.M2;
    }
    tab.f1[r] = f1;
    tab.tq1[r] = k.a1 * T.F_t + M.M1;
    if constexpr (!kWall) tab.tq2[r] = k.a2 * T.F_t + M.M2;
  }

  // The rolling law's couple; a law with an exact ledger split (ExactRollingSplit) then books its dissipation
  // from this step's trapezoid work (the previous couple is still in the row).
  template <class H>
  [[gnu::always_inline]] static RollingCouple rolling_moment(const ContactParams& p, const ContactTable& tab,
                                                             std::size_t r, const Row& row, double F_n, double dt,
                                                             H& hist) {
    if constexpr (ExactRollingSplit<Rolling>) {
      const double before = hist.r()[0][hist.row];
      RollingCouple M = Rolling::moment(p, row.b, row.k, F_n, dt, row.w1, row.w2, hist.r(), hist.row);
      Rolling::split(p, row.b, row.k, tab.M1[r], before, hist.r()[0][hist.row], dt, M);
      return M;
    } else {
      return Rolling::moment(p, row.b, row.k, F_n, dt, row.w1, row.w2, hist.r(), hist.row);
    }
  }

  template <bool kWall, bool kCommit = true>
  static void run_rows(const KernelContext& c, ContactTable& tab, LedgerStep& ledger) {
    const std::size_t n_owned = c.discs.n_owned();
    const double dt = c.dt;
    const Slots h(tab);
    const std::vector<ContactParams>& params = kWall ? c.params.walls() : c.params.pairs();
    LedgerStep L;
    Row row;
    for (std::size_t r = 0; r < tab.size(); ++r) {
      if (!kinematics<kWall>(c, tab, r, row)) {
        if (row.coincident) {
          L.worst_overlap = INFINITY;  // coincident centres: the run has failed
          L.worst_key = tab.key[r];
        }
        open_row<kCommit>(tab, r, h);
        continue;
      }
      const ContactKinematics& k = row.k;
      const bool book = static_cast<std::size_t>(tab.i1[r]) < n_owned;
      if (k.u_n <= 0.0) {
        // The contact opened this step: book the last half of the trapezoid, then forget its history.
        if (book) {
          L.W_n += 0.5 * tab.F_n[r] * k.v_n * dt;
          L.W_t += 0.5 * tab.F_t[r] * k.V_s * dt;
          if constexpr (Rolling::kActive) L.W_r += 0.5 * (tab.M1[r] * row.w1 + tab.M2[r] * row.w2) * dt;
          if constexpr (kWall) L.W_w += 0.5 * dot(tab.f1[r], row.v_wall) * dt;
        }
        open_row<kCommit>(tab, r, h);
        continue;
      }

      note_overlap<kWall>(c, k, tab.key[r], L);
      const ContactParams& p = params[static_cast<std::size_t>(tab.param[r])];
      const double F_n = Normal::force(p, row.b, k);
      History<kCommit> hist(h, r);
      const TangentialForce T = Tangential::force(p, row.b, k, F_n, dt, hist.t(), hist.row);
      RollingCouple M;
      if constexpr (Rolling::kActive) {
        if (p.rolling) {
          // The plain call for the linear normal law and a law without an exact split: the code of the
          // kernels that existed before the Hertz-Mindlin laws, unchanged.
          if constexpr (Normal::kStiffening) {  // the rolling law sees this contact's normal stiffness
            M = rolling_moment(Normal::linearised(p, row.b, k), tab, r, row, F_n, dt, hist);
          } else if constexpr (ExactRollingSplit<Rolling>) {
            M = rolling_moment(p, tab, r, row, F_n, dt, hist);
          } else {
            M = Rolling::moment(p, row.b, k, F_n, dt, row.w1, row.w2, hist.r(), hist.row);
          }
        }
      }
      const Vec2 f1 = T.F_t * k.t - F_n * k.n;
      if (book) book_work<kWall>(tab, r, row, F_n, T, M, f1, dt, L);
      store_row<kWall>(tab, r, k, F_n, T, M, f1);
    }
    ledger.add_terms(L, kTermKernel);
    if (L.worst_overlap > ledger.worst_overlap) {
      ledger.worst_overlap = L.worst_overlap;
      ledger.worst_key = L.worst_key;
      ledger.worst_at_wall = L.worst_at_wall;
    }
  }

  template <bool kWall>
  static void stored_rows(const KernelContext& c, ContactTable& tab, ContactSummary& e) {
    const Slots h(tab);
    const std::vector<ContactParams>& params = kWall ? c.params.walls() : c.params.pairs();
    Row row;
    for (std::size_t r = 0; r < tab.size(); ++r) {
      if (static_cast<std::size_t>(tab.i1[r]) >= c.discs.n_owned()) continue;
      if (!kinematics<kWall>(c, tab, r, row) || row.k.u_n <= 0.0) continue;
      const ContactParams& p = params[static_cast<std::size_t>(tab.param[r])];
      e.normal += Normal::stored(p, row.k);
      e.tangential += Tangential::stored(p, row.k, h.t.data(), r);
      const double F_n = tab.F_n[r];
      if (!(F_n > 0.0)) continue;
      ++e.contacts;
      if (kWall) ++e.wall_contacts;
      constexpr double kAtCap = 1.0 - 1e-9;
      if (Tangential::kFriction && std::fabs(tab.F_t[r]) >= kAtCap * p.mu * F_n) ++e.sliding;
      if constexpr (Rolling::kActive) {
        if (p.rolling) {
          const ContactParams q = Normal::linearised(p, row.b, row.k);
          e.rolling += Rolling::stored(q, row.b, row.k, F_n, h.r.data(), r);
          if (std::fabs(tab.M1[r]) >= kAtCap * Rolling::cap(q, row.k, F_n)) ++e.rolling_yield;
        }
      }
    }
  }
};

}  // namespace rondel
