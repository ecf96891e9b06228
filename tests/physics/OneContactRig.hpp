#pragma once
// A single contact (two discs, or a disc on a wall) stepped by the step's own serial core (physics/StepCore.hpp, the
// function Simulation's step calls: the half kick and drift, the fused contact kernel selected by select_kernel with
// the per-disc sums of ForceAssembly, the closing half kick). No neighbour list, no walls' motion: the one row is
// always present. Used by the frequency tests, stability test F4 (docs/validation.md section 5) and the law
// conformance tests.
//
// Geometry (docs/physics.md section 1 conventions):
//  - two discs: disc 1 (gid 1, radius R1) at the origin, disc 2 (gid 2, radius R2) at (R1 + R2 - u0, 0),
//    so n = (1, 0) and t = (0, 1);
//  - a wall (R2 = inf): the bottom wall y = 0, disc 1 at (0, R1 - u0), so n = (0, -1) and t = (1, 0).
// A constant central `preload` pushes the bodies together along the current line of centres (+preload n on
// disc 1, -preload n on disc 2; at a wall, along the wall's fixed normal), so that the contact rests at
// u_n = u0 when preload = k_n u0: a closed contact without gravity. Being central, the preload has the
// potential preload * |d| and no torque on a rotated pair, so it adds no stiffness at rest and no
// rigid-body instability (a preload of fixed direction would buckle a free pair). Gravity is separate.
#include <cmath>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ForceAssembly.hpp"
#include "core/Integrator.hpp"
#include "core/Vec2.hpp"
#include "core/Wall.hpp"
#include "physics/ContactKernel.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/StepCore.hpp"

namespace rondel::testing_rig {

class OneContactRig {
 public:
  OneContactRig(const LawSelection& laws, const ContactParams& p, double R1, double R2, double u0, double preload,
                Vec2 gravity = {}, double density = 2650.0, double thickness = 1.0)
      : params_(1), gravity_(gravity), preload_(preload) {
    wall_ = std::isinf(R2);
    params_.pair(0, 0) = p;
    params_.wall(0) = p;
    ops_ = select_kernel(laws);
    pairs_ = make_contact_table(laws, false);
    wall_rows_ = make_contact_table(laws, true);
    domain_ = Domain{-10.0, 10.0, -10.0, 10.0, false, false};
    if (wall_) {
      n = {0.0, -1.0};
      discs_.add(1, 0, R1, density, thickness, {0.0, R1 - u0});
      Wall w;
      w.kind = Wall::Kind::line;
      w.p0 = {0.0, 0.0};
      w.p1 = {1.0, 0.0};
      w.normal = {0.0, 1.0};
      walls_.push_back(w);
      wall_rows_.push(ContactKey{1, 0}, 0, 0, 0);
    } else {
      n = {1.0, 0.0};
      discs_.add(1, 0, R1, density, thickness, {0.0, 0.0});
      discs_.add(2, 0, R2, density, thickness, {R1 + R2 - u0, 0.0});
      pairs_.push(ContactKey{1, 2}, 0, 1, 0);
    }
    t = perp(n);
    x0_ = discs_.position;
    d0_ = separation();
    assembly_.build(discs_);
  }

  // Call after setting the initial velocities: forces at t = 0 with a zero increment, committing no
  // history (KernelOps::initial, as the Simulation constructor does), and the reference for the energy.
  void start(double dt) {
    dt_ = dt;
    StepCore::initial_forces(inputs());
    add_preload();
    stored0_ = stored();
  }

  // One step; the kernel's ledger terms of the step are given to *ledger when one is given.
  void step(LedgerStep* ledger = nullptr) {
    struct Preload : NoStepHooks {
      OneContactRig& rig;
      void after(LedgerStep&) { rig.add_preload(); }
    };
    const LedgerStep& work = core_.advance(inputs(), true, Preload{{}, *this});
    if (ledger) *ledger = work;
  }

  // Total mechanical energy relative to the resting state: kinetic + contact springs (as the kernel's
  // stored-energy pass reports them) + potential of the preload (preload * |d|) and of gravity.
  double energy() {
    double e = stored() - stored0_ + preload_ * (separation() - d0_);
    for (std::size_t i = 0; i < discs_.size(); ++i) {
      e += 0.5 * discs_.mass[i] * dot(discs_.velocity[i], discs_.velocity[i]) +
           0.5 * discs_.inertia[i] * discs_.omega[i] * discs_.omega[i];
      e -= dot(discs_.mass[i] * gravity_, discs_.position[i] - x0_[i]);
    }
    return e;
  }

  bool wall() const { return wall_; }
  DiscStore& discs() { return discs_; }
  const ContactTable& row_table() const { return wall_ ? wall_rows_ : pairs_; }
  ContactTable& row_table() { return wall_ ? wall_rows_ : pairs_; }
  // The contacts' stored energies as the kernel's stored-energy pass reports them (normal, tangential, rolling).
  ContactSummary summary() {
    return ops_.stored(KernelContext{discs_, domain_, walls_, params_, dt_}, pairs_, wall_rows_);
  }
  // Sliding velocity V_s and relative rotation rate of the contact from the full-step velocities.
  double sliding_velocity() const {
    const double u_n = overlap();
    const double a1 = discs_.radius[0] - 0.5 * u_n;
    double V = dot(discs_.velocity[0], t) + a1 * discs_.omega[0];
    if (!wall_) V += -dot(discs_.velocity[1], t) + (discs_.radius[1] - 0.5 * u_n) * discs_.omega[1];
    return V;
  }
  double rotation_rate() const { return discs_.omega[0] - (wall_ ? 0.0 : discs_.omega[1]); }
  double normal_velocity() const {  // (v2 - v1).n
    return dot((wall_ ? Vec2{} : discs_.velocity[1]) - discs_.velocity[0], n);
  }
  double overlap() const { return discs_.radius[0] + (wall_ ? 0.0 : discs_.radius[1]) - separation(); }
  // |d| between the centres, or the centre-to-wall distance.
  double separation() const {
    if (wall_) return walls_[0].proximity(discs_.position[0]).dist;
    const Vec2 d = discs_.position[1] - discs_.position[0];
    return std::sqrt(dot(d, d));
  }

  Vec2 n, t;  // the contact's normal (1 -> 2) and tangent at rest

 private:
  double stored() { return summary().total(); }
  StepInputs inputs() {
    return StepInputs{discs_, pairs_, wall_rows_, assembly_, ops_, domain_, walls_, params_, BodyForce{gravity_}, dt_};
  }
  // After the sums (the fixed discs finished): the preload.
  void add_preload() {
    if (wall_) {
      discs_.force[0] += preload_ * walls_[0].proximity(discs_.position[0]).n;
    } else {
      const Vec2 d = discs_.position[1] - discs_.position[0];
      const Vec2 f = (preload_ / std::sqrt(dot(d, d))) * d;
      discs_.force[0] += f;
      discs_.force[1] -= f;
    }
  }

  bool wall_ = false;
  ContactParamTable params_;
  Vec2 gravity_;
  KernelOps ops_;
  DiscStore discs_;
  Domain domain_;
  WallSet walls_;
  ContactTable pairs_, wall_rows_;
  ForceAssembly assembly_;
  StepCore core_;
  double preload_ = 0.0;
  std::vector<Vec2> x0_;
  double d0_ = 0.0;
  double dt_ = 0.0;
  double stored0_ = 0.0;
};

// Angular frequency of a signal sampled every dt, from its zero crossings, averaged over every half period
// between the first and the last crossing; 0 when fewer than three crossings. Each crossing is located on
// the cubic through the four samples around it (third-order accurate, so a few samples per period suffice).
inline double frequency_from_zero_crossings(const std::vector<double>& s, double dt) {
  std::vector<double> times;
  for (std::size_t k = 2; k + 1 < s.size(); ++k) {
    const double y0 = s[k - 2], y1 = s[k - 1], y2 = s[k], y3 = s[k + 1];
    if (!((y1 < 0.0 && y2 >= 0.0) || (y1 > 0.0 && y2 <= 0.0))) continue;
    // Lagrange cubic through x = -1, 0, 1, 2 (x = 0 at sample k - 1).
    auto p = [&](double x) {
      return -y0 * x * (x - 1.0) * (x - 2.0) / 6.0 + y1 * (x + 1.0) * (x - 1.0) * (x - 2.0) / 2.0 -
             y2 * (x + 1.0) * x * (x - 2.0) / 2.0 + y3 * (x + 1.0) * x * (x - 1.0) / 6.0;
    };
    double x = y1 / (y1 - y2);  // the linear estimate, then Newton on the cubic (numerical slope)
    for (int it = 0; it < 20; ++it) {
      const double h = 1e-6, slope = (p(x + h) - p(x - h)) / (2.0 * h);
      if (slope == 0.0) break;
      const double dx = p(x) / slope;
      x -= dx;
      if (std::fabs(dx) < 1e-14) break;
    }
    times.push_back(dt * (static_cast<double>(k - 1) + x));
  }
  if (times.size() < 3) return 0.0;
  const double half_period = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  return M_PI / half_period;
}

// Velocity Verlet's frequency for a mode of exact angular frequency w (w dt < 2).
inline double verlet_frequency(double w, double dt) { return (2.0 / dt) * std::asin(0.5 * w * dt); }

}  // namespace rondel::testing_rig
