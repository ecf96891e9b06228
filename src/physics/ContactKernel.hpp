#pragma once
// The fused contact kernel: one pass over the contact rows, templated on the selected (normal,
// tangential, rolling) laws so that a `none` law compiles to nothing (docs/design.md section 3). Every row is
// evaluated in its canonical frame from the discs' positions and half-step velocities, and its force and
// torques are added at once to its two discs' sums (ForceSums). The rows are in ascending key order (lower
// gid, higher gid), so each disc receives its terms in ascending partner gid: first the rows where it is
// disc 2 (partners of lower gid, in ascending order), then the rows where it is disc 1 (ascending higher gid),
// then its wall rows (the wall table comes after the pair table, in wall id order). That is the order of
// docs/design.md section 5, whatever the storage order of the discs, the rank count or when the list was
// built; ForceAssembly starts each sum with the body force and finishes the fixed discs.
//
// Energy ledger (docs/physics.md section 5): the work of each contact on the relative motion is integrated
// with the half-step velocities and the trapezoid of last and this step's force,
//   dW_n = (F_n' + F_n)/2 v_n dt,  dW_t = (F_t' + F_t)/2 V_s dt,  dW_r = sum_i (M_i' + M_i)/2 omega_i dt,
// and a moving wall's work on a disc is (f' + f)/2 . v_wall dt, v_wall its surface velocity at the contact
// point; a rotating wall (Omega) also works through the couple, (M1' + M1)/2 Omega dt, while the rolling
// term of a wall row is (M1' + M1)/2 (omega1 - Omega) dt (docs/physics.md section 8). The rows' (F' + F) v terms are
// summed and the sums multiplied by dt/2 once per pass; for a law whose couple on disc 2 is -M1, the rolling term is
// (M1' + M1)(omega1 - omega2). The laws report Coulomb slip, rolling plastic and dashpot work, brittle-break
// releases and the normal law's hysteresis. A row is booked by the rank that owns its disc 1, so a border pair computed
// on two ranks counts once. A pair across a moving cell's boundary also books the cell's work on its discs, dv . (f1' +
// f1) dt/2, dv the velocity offset of disc 2's image (W_cell, docs/physics.md section 10).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ForceAssembly.hpp"
#include "core/LedgerTerms.hpp"
#include "core/Wall.hpp"
#include "physics/CellCrossings.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/ContactPass.hpp"
#include "physics/LawConcepts.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

template <class Normal, class Tangential, class Rolling>
struct ContactKernel {
  static constexpr std::size_t kTSlots = Tangential::slots.size();
  static constexpr std::size_t kRSlots = Rolling::slots.size();
  static constexpr std::size_t kNSlots = Normal::slots.size();
  static constexpr int kCouples = couple_columns<Rolling>();

  // The pair rows take the standing box's minimum image or, in a cell that tilts or moves, the sheared one with
  // the image's velocity (Lees-Edwards): one test per pass, and the standing box's pass as before.
  static void run(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows, ForceSums sums,
                  LedgerStep& ledger) {
    if (c.domain.standing())
      run_rows<false, true, MinimumImage>(c, pairs, sums, ledger);
    else
      run_rows<false, true, ShearedImage>(c, pairs, sums, ledger);
    run_rows<true>(c, wall_rows, sums, ledger);
  }

  // The forces of the initial state for the first half kick (c.dt = 0): the laws see a copy of each
  // row's history, so a capping rule that resets a spring (a dashpot alone above the cap) commits
  // nothing, and no work is booked. The run starts from the history it was given.
  static void initial_forces(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows, ForceSums sums) {
    LedgerStep unused;
    if (c.domain.standing())
      run_rows<false, false, MinimumImage>(c, pairs, sums, unused);
    else
      run_rows<false, false, ShearedImage>(c, pairs, sums, unused);
    run_rows<true, false>(c, wall_rows, sums, unused);
  }

  static ContactSummary stored_energy(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows) {
    ContactSummary e;
    if (c.domain.standing())
      stored_rows<false, MinimumImage>(c, pairs, e);
    else
      stored_rows<false, ShearedImage>(c, pairs, e);
    stored_rows<true>(c, wall_rows, e);
    return e;
  }

 private:
  struct Slots {
    std::array<double*, kTSlots + 1> t{};
    std::array<double*, kRSlots + 1> r{};
    std::array<double*, kNSlots + 1> n{};
    explicit Slots(ContactTable& tab) {
      for (std::size_t s = 0; s < kTSlots; ++s) t[s] = tab.slot[s].data();
      for (std::size_t s = 0; s < kRSlots; ++s) r[s] = tab.slot[kTSlots + s].data();
      for (std::size_t s = 0; s < kNSlots; ++s) n[s] = tab.slot[kTSlots + kRSlots + s].data();
    }
  };

  // The history the laws of row r write to, as the laws' History structs: the table's columns (committed), or a
  // copy of the row's values that is dropped afterwards (scratch; the structs then refer to the copy).
  using THistory = typename Tangential::History;
  using RHistory = typename Rolling::History;
  using NHistory = typename Normal::History;
  struct CommittedHistory {
    THistory t;
    RHistory r;
    NHistory n;
    CommittedHistory(const Slots& slots, std::size_t row)
        : t(history_row<THistory, kTSlots>(slots.t.data(), row)),
          r(history_row<RHistory, kRSlots>(slots.r.data(), row)),
          n(history_row<NHistory, kNSlots>(slots.n.data(), row)) {}
  };
  struct ScratchValues {
    std::array<double, kTSlots + 1> tv{};
    std::array<double, kRSlots + 1> rv{};
    std::array<double, kNSlots + 1> nv{};
    std::array<double*, kTSlots + 1> tp{};
    std::array<double*, kRSlots + 1> rp{};
    std::array<double*, kNSlots + 1> np{};
    ScratchValues(const Slots& slots, std::size_t row) {
      for (std::size_t s = 0; s < kTSlots; ++s) tv[s] = slots.t[s][row], tp[s] = &tv[s];
      for (std::size_t s = 0; s < kRSlots; ++s) rv[s] = slots.r[s][row], rp[s] = &rv[s];
      for (std::size_t s = 0; s < kNSlots; ++s) nv[s] = slots.n[s][row], np[s] = &nv[s];
    }
  };
  struct ScratchHistory : ScratchValues {
    THistory t;
    RHistory r;
    NHistory n;
    ScratchHistory(const Slots& slots, std::size_t row)
        : ScratchValues(slots, row),
          t(history_row<THistory, kTSlots>(this->tp.data(), 0)),
          r(history_row<RHistory, kRSlots>(this->rp.data(), 0)),
          n(history_row<NHistory, kNSlots>(this->np.data(), 0)) {}
    ScratchHistory(const ScratchHistory&) = delete;  // t, r and n refer into this object
  };
  template <bool kCommit>
  using History = std::conditional_t<kCommit, CommittedHistory, ScratchHistory>;

  // The discs' columns the kernel reads, as plain pointers taken once per pass (a store to a row or a sum
  // cannot make the compiler reload them).
  struct DiscView {
    const Vec2 *x, *v;
    const double *w, *R, *m, *I;
    std::size_t n_owned;
    explicit DiscView(const DiscStore& D)
        : x(D.position.data()),
          v(D.velocity.data()),
          w(D.omega.data()),
          R(D.radius.data()),
          m(D.mass.data()),
          I(D.inertia.data()),
          n_owned(D.n_owned()) {}
  };

  // One row's motion: the kinematics in the canonical frame, the bodies, both spins and the wall's velocity.
  struct Row {
    ContactKinematics k;
    ContactBodies b;
    double w1 = 0.0, w2 = 0.0;
    Vec2 v_wall;
  };
  enum class Found { apart, contact, coincident };

  // Kinematics of row r; `apart` when the discs are apart and the row carries no force (nothing to do),
  // `coincident` when two centres coincide (no normal exists: reported as a failed run).
  // A pass that books the cell's work passes `crossings`: a moving cell's rows across its boundary are noted
  // (CellCrossings.hpp).
  template <bool kWall, class Image>
  [[gnu::always_inline]] static Found kinematics(const DiscView& D, const Image& image, const WallSet& walls,
                                                 const ContactTable& tab, std::size_t r, Row& row,
                                                 Crossings* crossings = nullptr) {
    const auto i = static_cast<std::size_t>(tab.i1[r]);
    const auto j = static_cast<std::size_t>(tab.i2[r]);
    const bool loaded = tab.F_n[r] != 0.0 || tab.F_t[r] != 0.0;
    if constexpr (kWall) {
      const Wall& w = walls[j];
      const Wall::Proximity prox = w.proximity(D.x[i]);
      if (prox.dist >= D.R[i] && !loaded) return Found::apart;
      row.w1 = D.w[i];
      if (w.rotates()) {  // the surface velocity at the contact point, and the wall's spin (physics.md section 8)
        row.w2 = w.omega;
        row.v_wall = w.surface_velocity(D.x[i] + wall_lever(D.R[i], prox.dist) * prox.n);
      } else {
        row.v_wall = w.velocity;
      }
      row.k = disc_wall_kinematics(prox.n, prox.dist, D.R[i], D.v[i], row.v_wall, row.w1, row.w2);
      row.b = disc_wall_bodies(D.m[i], D.I[i]);
    } else {
      Vec2 dv;  // in a moving cell, the velocity offset of disc 2's image (Lees-Edwards)
      Vec2 d;
      if constexpr (Image::kMoving)
        d = image.separation(D.x[i], D.x[j], dv, [&] {
          if (crossings) note_crossing(*crossings, r, tab);
        });
      else
        d = image.separation(D.x[i], D.x[j], dv);
      const double dist2 = dot(d, d);
      const double R1 = D.R[i], R2 = D.R[j];
      const double Rs = R1 + R2;
      if (dist2 >= Rs * Rs && !loaded) return Found::apart;
      if (dist2 == 0.0) return Found::coincident;
      row.w1 = D.w[i];
      row.w2 = D.w[j];
      const Vec2 v2 = Image::kMoving ? D.v[j] + dv : D.v[j];
      row.k = disc_disc_kinematics(d, std::sqrt(dist2), R1, R2, D.v[i], v2, row.w1, row.w2);
      row.b = disc_disc_bodies(D.m[i], D.m[j], D.I[i], D.I[j]);
    }
    return Found::contact;
  }

  // A row whose contact is open carries no force and no history: its values are set to +0. Unconditionally:
  // testing them first costs more than the stores (their cache lines are written anyway by the rows around).
  static void clear(double& x) { x = 0.0; }
  template <bool kWall, bool kCommit>
  static void open_row(ContactTable& tab, std::size_t r, const Slots& h) {
    if constexpr (kCommit) {
      for (std::size_t s = 0; s < kTSlots; ++s) clear(h.t[s][r]);
      for (std::size_t s = 0; s < kRSlots; ++s) clear(h.r[s][r]);
      for (std::size_t s = 0; s < kNSlots; ++s) clear(h.n[s][r]);
    }
    clear(tab.F_n[r]);
    clear(tab.F_t[r]);
    if constexpr (kCouples > 0) clear(tab.M1[r]);
    if constexpr (kCouples > 1) clear(tab.M2[r]);
    if constexpr (kWall) clear(tab.f1[r].x), clear(tab.f1[r].y);
  }

  // The last step's couple on disc 1 (0 without a rolling law).
  static double last_M1(const ContactTable& tab, std::size_t r) {
    if constexpr (kCouples > 0)
      return tab.M1[r];
    else
      return 0.0;
  }
  // The last step's couple on disc 2: its own column, or -M1 (the same bits as the law's -M).
  static double last_M2(const ContactTable& tab, std::size_t r) {
    if constexpr (kCouples > 1)
      return tab.M2[r];
    else
      return -tab.M1[r];
  }

  // The worst overlap above the context's limit (u_n / smaller radius), and where.
  template <bool kWall>
  [[gnu::always_inline]] static void note_overlap(double overlap_limit, const ContactKinematics& k,
                                                  const ContactKey& key, WorstOverlap& L) {
    const double R_small = kWall ? k.R1 : std::min(k.R1, k.R2);
    if (k.u_n > overlap_limit * R_small && k.u_n > L.worst_overlap * R_small) {
      L.worst_overlap = k.u_n / R_small;
      L.worst_key = key;
      L.worst_at_wall = kWall;
    }
  }

  // The ledger's sums of a pass, two to a 16-byte register: the kernel's loop has more live values than the
  // processor has registers, and sums kept in memory cost a load and a store per row each. A packed addition
  // adds each lane exactly as a scalar one would (the same bits). The works are without the factor dt/2
  // (applied to the pass's totals, see the header); every dissipation term is >= 0.
  using Pair = double __attribute__((vector_size(16)));
  struct PassSums {
    Pair work{0.0, 0.0};  // W_n, W_t
    Pair roll{0.0, 0.0};  // W_r, D_slip
    Pair loss{0.0, 0.0};  // D_r_plastic, D_r_dashpot
    double W_w = 0.0, E_r_break = 0.0;
    double W_cell = 0.0;
    double D_n_hyst = 0.0;
    // Onto the step's ledger terms, with the works' factor dt/2.
    void book(double dt, LedgerStep& L) const {
      const double half_dt = 0.5 * dt;
      L.W_n += half_dt * work[0], L.W_t += half_dt * work[1], L.W_r += half_dt * roll[0];
      L.W_w += half_dt * W_w;
      L.W_cell += half_dt * W_cell;
      L.D_slip += roll[1], L.D_r_plastic += loss[0], L.D_r_dashpot += loss[1], L.E_r_break += E_r_break;
      if constexpr (hysteretic<Normal>()) L.D_n_hyst += D_n_hyst;
    }
  };

  // The ledger's share of a booked row: the trapezoid of last and this step's force and couples, and the
  // laws' dissipation.
  template <bool kWall>
  [[gnu::always_inline]] static void book_work(const ContactTable& tab, std::size_t r, const Row& row,
                                               const NormalForce& N, const TangentialForce& T, const RollingCouple& M,
                                               Vec2 f1, PassSums& S) {
    const ContactKinematics& k = row.k;
    S.work += Pair{(tab.F_n[r] + N.F_n) * k.v_n, (tab.F_t[r] + T.F_t) * k.V_s};
    if constexpr (hysteretic<Normal>()) S.D_n_hyst += N.hysteresis;
    double W_r = 0.0;
    if constexpr (kCouples > 1 && !kWall)
      W_r = (tab.M1[r] + M.M1) * row.w1 + (tab.M2[r] + M.M2) * row.w2;
    else if constexpr (kCouples > 0)
      W_r = (tab.M1[r] + M.M1) * k.thetadot_r;  // at a wall: its couple on the wall does no work on the discs
    S.roll += Pair{W_r, T.slip};
    if constexpr (Rolling::kActive) {
      if constexpr (sparse_loss<Rolling>()) {
        if (M.plastic != 0.0 || M.dashpot != 0.0) [[unlikely]]
          S.loss += Pair{M.plastic, M.dashpot};
      } else {
        S.loss += Pair{M.plastic, M.dashpot};
      }
      if constexpr (breaks<Rolling>()) S.E_r_break += M.released;
    }
    if constexpr (kWall) {
      S.W_w += dot(tab.f1[r] + f1, row.v_wall);
      // A rotating wall: the couple on the disc works on the wall's spin too, (M1' + M1) Omega.
      if constexpr (kCouples > 0)
        if (row.w2 != 0.0) S.W_w += (tab.M1[r] + M.M1) * row.w2;
    }
  }

  // This step's result into the row's columns: the state the next step starts from.
  template <bool kWall>
  [[gnu::always_inline]] static void store_row(ContactTable& tab, std::size_t r, double F_n, const TangentialForce& T,
                                               const RollingCouple& M, Vec2 f1) {
    tab.F_n[r] = F_n;
    tab.F_t[r] = T.F_t;
    if constexpr (kCouples > 0) tab.M1[r] = M.M1;
    if constexpr (kCouples > 1) tab.M2[r] = M.M2;
    if constexpr (kWall) tab.f1[r] = f1;
  }

  // The last half of the trapezoid of a contact that opened this step (its forces and couples fall to zero).
  template <bool kWall>
  [[gnu::always_inline]] static void book_opening(const ContactTable& tab, std::size_t r, const Row& row, PassSums& S) {
    const ContactKinematics& k = row.k;
    double W_r = 0.0;
    if constexpr (Rolling::kActive) {
      if constexpr (kWall)
        W_r = tab.M1[r] * k.thetadot_r;
      else
        W_r = tab.M1[r] * row.w1 + last_M2(tab, r) * row.w2;
    }
    S.work += Pair{tab.F_n[r] * k.v_n, tab.F_t[r] * k.V_s};
    S.roll += Pair{W_r, 0.0};
    if constexpr (kWall) {
      S.W_w += dot(tab.f1[r], row.v_wall);
      if constexpr (Rolling::kActive)
        if (row.w2 != 0.0) S.W_w += tab.M1[r] * row.w2;
    }
  }

  // The rolling law's couple of a row (none where the pair has no rolling resistance); a normal law that
  // stiffens shows the rolling law this contact's normal stiffness and dashpot (its linearised parameters).
  template <class H>
  [[gnu::always_inline]] static RollingCouple couple(const ContactInput& in, const ContactTable& tab, std::size_t r,
                                                     const Row& row, H& hist) {
    RollingCouple M;
    if constexpr (Rolling::kActive) {
      if (rolls_every_row<Rolling>() || in.p.rolling) [[likely]] {
        if constexpr (Normal::kStiffening) {
          const ContactParams q = Normal::linearised(ContactInput{in.p, row.b, row.k});
          M = Rolling::moment(ContactInput{q, row.b, row.k, in.F_n, in.dt, row.w1, row.w2, last_M1(tab, r)}, hist.r);
        } else {
          M = Rolling::moment(in, hist.r);
        }
      }
    }
    return M;
  }

  // The row's terms of its discs' sums, in row order (see the header): +f1 and its torque on disc 1, -f1 and its
  // torque on disc 2.
  template <bool kWall>
  [[gnu::always_inline]] static void add_to_sums(const ContactTable& tab, std::size_t r, std::size_t i,
                                                 const ContactKinematics& k, const TangentialForce& T,
                                                 const RollingCouple& M, Vec2 f1, Vec2* sum_F, double* sum_T) {
    sum_F[i] += f1;
    sum_T[i] += k.a1 * T.F_t + M.M1;
    if constexpr (!kWall) {
      const auto j = static_cast<std::size_t>(tab.i2[r]);
      sum_F[j] -= f1;
      sum_T[j] += k.a2 * T.F_t + M.M2;
    }
  }

  // A pass's worst overlap into the step's.
  static void merge(const WorstOverlap& L, LedgerStep& ledger) {
    if (L.worst_overlap > ledger.worst_overlap) {
      ledger.worst_overlap = L.worst_overlap;
      ledger.worst_key = L.worst_key;
      ledger.worst_at_wall = L.worst_at_wall;
    }
  }

  // The image of a pass: `Image` for pair rows, none for wall rows.
  template <bool kWall, class Image>
  using PassImage = std::conditional_t<kWall, NoImage, Image>;

  template <bool kWall, bool kCommit = true, class Image = MinimumImage>
  static void run_rows(const KernelContext& c, ContactTable& tab, ForceSums sums, LedgerStep& ledger) {
    const DiscView D(c.discs);
    const PassImage<kWall, Image> image(c.domain);
    const double dt = c.dt, overlap_limit = c.overlap_limit;
    const Slots h(tab);
    const ContactParams* const params = (kWall ? c.params.walls() : c.params.pairs()).data();
    Vec2* const sum_F = sums.force;
    double* const sum_T = sums.torque;
    WorstOverlap L;
    PassSums S;
    static thread_local Crossings crossings;  // reused pass to pass
    crossings.clear();
    const std::size_t n_rows = tab.size();
    for (std::size_t r = 0; r < n_rows; ++r) {
      Row row;
      const Found found = kinematics<kWall>(D, image, c.walls, tab, r, row, kCommit ? &crossings : nullptr);
      if (found != Found::contact) {
        if (found == Found::coincident) {
          L.worst_overlap = INFINITY;  // coincident centres: the run has failed
          L.worst_key = tab.key[r];
        }
        open_row<kWall, kCommit>(tab, r, h);
        continue;
      }
      const ContactKinematics& k = row.k;
      const auto i = static_cast<std::size_t>(tab.i1[r]);
      const bool book = i < D.n_owned;
      if (k.u_n <= 0.0) {
        // The contact opened this step: book the last half of the trapezoid, then forget its history.
        if (book) book_opening<kWall>(tab, r, row, S);
        open_row<kWall, kCommit>(tab, r, h);
        continue;
      }

      note_overlap<kWall>(overlap_limit, k, tab.key[r], L);
      const ContactParams& p = params[tab.param[r]];
      History<kCommit> hist(h, r);
      const NormalForce N = Normal::force(ContactInput{p, row.b, k}, hist.n);
      const double F_n = N.F_n;
      const ContactInput in{p, row.b, k, F_n, dt, row.w1, row.w2, last_M1(tab, r)};
      const TangentialForce T = Tangential::force(in, hist.t);
      const RollingCouple M = couple(in, tab, r, row, hist);
      const Vec2 f1 = T.F_t * k.t - F_n * k.n;
      if (book) book_work<kWall>(tab, r, row, N, T, M, f1, S);
      store_row<kWall>(tab, r, F_n, T, M, f1);
      add_to_sums<kWall>(tab, r, i, k, T, M, f1, sum_F, sum_T);
    }
    if constexpr (!kWall && Image::kMoving && kCommit)
      S.W_cell = crossings_work(S.W_cell, image, D.x, D.v, D.w, D.R, D.n_owned, tab, crossings);
    S.book(dt, ledger);  // onto the step's sums (0 + x is x: the same bits as a pass's own sums added)
    merge(L, ledger);
  }

  template <bool kWall, class Image = MinimumImage>
  static void stored_rows(const KernelContext& c, ContactTable& tab, ContactSummary& e) {
    const Slots h(tab);
    const std::vector<ContactParams>& params = kWall ? c.params.walls() : c.params.pairs();
    const DiscView D(c.discs);
    const PassImage<kWall, Image> image(c.domain);
    for (std::size_t r = 0; r < tab.size(); ++r) {
      if (static_cast<std::size_t>(tab.i1[r]) >= c.discs.n_owned()) continue;
      Row row;
      if (kinematics<kWall>(D, image, c.walls, tab, r, row) != Found::contact || row.k.u_n <= 0.0) continue;
      const ContactParams& p = params[static_cast<std::size_t>(tab.param[r])];
      const ContactInput geometry{p, row.b, row.k};
      e.normal += Normal::stored(geometry, history_row<NHistory, kNSlots>(h.n.data(), r));
      e.tangential += Tangential::stored(geometry, history_row<THistory, kTSlots>(h.t.data(), r));
      const double F_n = tab.F_n[r];
      if (!(F_n > 0.0)) continue;
      ++e.contacts;
      if (kWall) ++e.wall_contacts;
      constexpr double kAtCap = 1.0 - 1e-9;
      if (Tangential::kFriction && std::fabs(tab.F_t[r]) >= kAtCap * p.mu * F_n) ++e.sliding;
      if constexpr (Rolling::kActive) {
        if (p.rolling) {
          const ContactParams q = Normal::linearised(geometry);
          const ContactInput in{q, row.b, row.k, F_n};
          e.rolling += Rolling::stored(in, history_row<RHistory, kRSlots>(h.r.data(), r));
          if (std::fabs(tab.M1[r]) >= kAtCap * Rolling::cap(in)) ++e.rolling_yield;
        }
      }
    }
  }
};

}  // namespace rondel
