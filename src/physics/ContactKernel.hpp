#pragma once
// The fused contact kernel: one pass over the contact rows, templated on the selected (normal,
// tangential, rolling) laws so that a `none` law compiles to nothing (DESIGN.md section 3). Every row is
// evaluated in its canonical frame from the discs' positions and half-step velocities; its forces go to
// the row's columns and are summed per disc afterwards (ForceAssembly), in ascending partner gid.
//
// Energy ledger (PHYSICS.md section 5): the work of each contact on the relative motion is integrated
// with the half-step velocities and the trapezoid of last and this step's force,
//   dW_n = (F_n' + F_n)/2 v_n dt,  dW_t = (F_t' + F_t)/2 V_s dt,  dW_r = sum_i (M_i' + M_i)/2 omega_i dt,
// and a moving wall's work on a disc is (f' + f)/2 . v_wall dt. A row is booked by the rank that owns
// its disc 1, so a border pair computed on two ranks counts once.
#include <array>
#include <cstddef>
#include <string>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Errors.hpp"
#include "core/Wall.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

struct LedgerStep {
  double W_n = 0.0, W_t = 0.0, W_r = 0.0, W_w = 0.0;
};

struct KernelContext {
  const DiscStore& discs;
  const Domain& domain;
  const WallSet& walls;
  const ContactParamTable& params;
  double dt;
};

template <class Normal, class Tangential, class Rolling>
struct ContactKernel {
  static constexpr std::size_t kTSlots = Tangential::slots.size();
  static constexpr std::size_t kRSlots = Rolling::slots.size();

  static void run(const KernelContext& c, ContactTable& pairs, ContactTable& wall_rows, LedgerStep& ledger) {
    run_rows<false>(c, pairs, ledger);
    run_rows<true>(c, wall_rows, ledger);
  }

 private:
  static void open_row(ContactTable& tab, std::size_t r, double* const* th, double* const* rh) {
    for (std::size_t s = 0; s < kTSlots; ++s) th[s][r] = 0.0;
    for (std::size_t s = 0; s < kRSlots; ++s) rh[s][r] = 0.0;
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

  template <bool kWall>
  static void run_rows(const KernelContext& c, ContactTable& tab, LedgerStep& ledger) {
    const DiscStore& D = c.discs;
    const std::size_t n_owned = D.n_owned();
    const double dt = c.dt;
    std::array<double*, kTSlots + 1> th{};
    std::array<double*, kRSlots + 1> rh{};
    for (std::size_t s = 0; s < kTSlots; ++s) th[s] = tab.slot[s].data();
    for (std::size_t s = 0; s < kRSlots; ++s) rh[s] = tab.slot[kTSlots + s].data();
    const std::vector<ContactParams>& params = kWall ? c.params.walls() : c.params.pairs();
    LedgerStep L;

    for (std::size_t r = 0; r < tab.size(); ++r) {
      const std::size_t i = static_cast<std::size_t>(tab.i1[r]);
      const std::size_t j = static_cast<std::size_t>(tab.i2[r]);
      ContactKinematics k;
      ContactBodies b;
      double w2 = 0.0;
      Vec2 v_wall;
      if constexpr (kWall) {
        const Wall& w = c.walls[j];
        const Wall::Proximity prox = w.proximity(D.position[i]);
        if (prox.dist >= D.radius[i] && tab.F_n[r] == 0.0 && tab.F_t[r] == 0.0) {
          open_row(tab, r, th.data(), rh.data());
          continue;
        }
        v_wall = w.velocity;
        k = disc_wall_kinematics(prox.n, prox.dist, D.radius[i], D.velocity[i], v_wall, D.omega[i]);
        b = disc_wall_bodies(D.mass[i], D.inertia[i]);
      } else {
        const Vec2 d = c.domain.separation(D.position[i], D.position[j]);
        const double dist2 = dot(d, d);
        const double Rs = D.radius[i] + D.radius[j];
        if (dist2 >= Rs * Rs && tab.F_n[r] == 0.0 && tab.F_t[r] == 0.0) {
          open_row(tab, r, th.data(), rh.data());
          continue;
        }
        if (dist2 == 0.0)
          throw InstabilityError("discs " + std::to_string(D.gid[i]) + " and " + std::to_string(D.gid[j]) +
                                 " have coincident centres");
        w2 = D.omega[j];
        k = disc_disc_kinematics(d, std::sqrt(dist2), D.radius[i], D.radius[j], D.velocity[i], D.velocity[j],
                                 D.omega[i], w2);
        b = disc_disc_bodies(D.mass[i], D.mass[j], D.inertia[i], D.inertia[j]);
      }
      const bool book = i < n_owned;
      const double w1 = D.omega[i];

      if (k.u_n <= 0.0) {
        // The contact opened this step: book the last half of the trapezoid, then forget its history.
        if (book) {
          L.W_n += 0.5 * tab.F_n[r] * k.v_n * dt;
          L.W_t += 0.5 * tab.F_t[r] * k.V_s * dt;
          if constexpr (Rolling::kActive) L.W_r += 0.5 * (tab.M1[r] * w1 + tab.M2[r] * w2) * dt;
          if constexpr (kWall) L.W_w += 0.5 * dot(tab.f1[r], v_wall) * dt;
        }
        open_row(tab, r, th.data(), rh.data());
        continue;
      }

      const ContactParams& p = params[static_cast<std::size_t>(tab.param[r])];
      const double F_n = Normal::force(p, b, k);
      const double F_t = Tangential::force(p, b, k, F_n, dt, th.data(), r);
      RollingCouple M;
      if constexpr (Rolling::kActive) M = Rolling::moment(p, b, k, F_n, dt, w1, w2, rh.data(), r);

      const Vec2 f1 = F_t * k.t - F_n * k.n;
      if (book) {
        L.W_n += 0.5 * (tab.F_n[r] + F_n) * k.v_n * dt;
        L.W_t += 0.5 * (tab.F_t[r] + F_t) * k.V_s * dt;
        if constexpr (Rolling::kActive)
          L.W_r += 0.5 * ((tab.M1[r] + M.M1) * w1 + (tab.M2[r] + M.M2) * w2) * dt;
        if constexpr (kWall) L.W_w += 0.5 * dot(tab.f1[r] + f1, v_wall) * dt;
      }
      tab.F_n[r] = F_n;
      tab.F_t[r] = F_t;
      if constexpr (Rolling::kActive) {
        tab.M1[r] = M.M1;
        tab.M2[r] = M.M2;
      }
      tab.f1[r] = f1;
      tab.tq1[r] = k.a1 * F_t + M.M1;
      if constexpr (!kWall) tab.tq2[r] = k.a2 * F_t + M.M2;
    }
    ledger.W_n += L.W_n;
    ledger.W_t += L.W_t;
    ledger.W_r += L.W_r;
    ledger.W_w += L.W_w;
  }
};

}  // namespace rondel
