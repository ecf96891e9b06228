#pragma once
#include <cstdint>
#include <string>

#include "app/Boundaries.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"
#include "physics/ContactPass.hpp"

namespace rondel {

// Macroscopic measures of the assembly (compression positive, stresses per thickness [Pa]):
//  - box: the sample between the box walls (width, height), the walls' normal stresses; the shear stress
//    on the top wall wall_tau = -F_x / (W t) (positive when the discs resist its motion in +x) and the
//    shear displacement shear_disp = x of the top wall - x of the bottom wall (0 at the start of a stage);
//  - Love-Weber average stress sigma = -(1/(A t)) [sum over disc pairs d (x) f1 + sum over wall contacts
//    a1 n (x) f1] with A the box area (the domain's without box walls), its principal values s1 >= s3;
//  - strains from the box: axial (vertical) (H0 - H)/H0, lateral (W0 - W)/W0, volumetric 1 - A/A0;
//  - planar void ratio (A - A_solid)/A_solid, coordination, mean and spread of the disc rotations theta,
//    (of the free discs: glued discs are part of their wall), fractions of loaded contacts sliding (|F_t| = mu F_n) and
//    yielded in rolling (|M| at the law's cap);
//  - the cell (docs/physics.md section 10): its lengths and tilt, the shear strain gamma = (tilt + flips L_x) / L_y
//    (flips counted with their sign), the kinetic stress K = (1/(A t)) sum m (u - U) (x) (u - U) of the velocities
//    u = v - L (x - x0) apart from the mean flow and of their mass-weighted mean U, the pressure p = (sxx + syy + kxx +
//    kyy) / 2, the shear stress tau = -(sxy + kxy) (positive when the discs resist a shear at cell.rate_xy > 0), mu =
//    tau / p, the inertial number I = |rate_xy| d / sqrt(p / rho) (d the mean diameter, rho the discs' mean density; 0
//    when p <= 0) and the solid fraction phi = A_solid / A.
struct MeasuresRow {
  std::int64_t step = 0;
  double time = 0.0;
  double width = 0.0, height = 0.0;
  double wall_sxx = 0.0, wall_syy = 0.0, wall_tau = 0.0, shear_disp = 0.0;
  double sxx = 0.0, syy = 0.0, sxy = 0.0, s1 = 0.0, s3 = 0.0;
  double eps_axial = 0.0, eps_lateral = 0.0, eps_vol = 0.0;
  double void_ratio = 0.0, coordination = 0.0;
  double rotation_mean = 0.0, rotation_std = 0.0;
  double sliding_fraction = 0.0, rolling_yield_fraction = 0.0;
  double cell_lx = 0.0, cell_ly = 0.0, cell_tilt = 0.0, shear_strain = 0.0;
  double kxx = 0.0, kyy = 0.0, kxy = 0.0, pressure = 0.0, tau = 0.0, mu = 0.0, inertial = 0.0, phi = 0.0;

  static std::string header();
  std::string csv() const;
};

// Computes a MeasuresRow from the discs, their rows and the walls (whose loads are measured already);
// collective. `box0` is the box at the start of the stage, `contacts` the kernel's contact summary.
class Measures {
 public:
  // `flips`: the cell's flips so far, with their sign (+1 when the tilt fell by L_x).
  Measures(const Domain& domain, double thickness, const Communicator& comm, std::int64_t flips = 0)
      : domain_(domain), thickness_(thickness), comm_(comm), flips_(flips) {}

  MeasuresRow row(std::int64_t step, double time, const DiscStore& discs, const ContactTable& pairs,
                  const ContactTable& wall_rows, const WallSet& walls, const BoxGeometry& box0,
                  const ContactSummary& contacts) const;

 private:
  void box_stresses(MeasuresRow& m, const WallSet& walls, const BoxGeometry& g) const;
  void love_weber(MeasuresRow& m, const DiscStore& discs, const ContactTable& pairs, const ContactTable& wall_rows,
                  const WallSet& walls, double area) const;
  void disc_statistics(MeasuresRow& m, const DiscStore& discs, double area, const ContactSummary& contacts) const;
  void cell_measures(MeasuresRow& m, const DiscStore& discs, double area) const;

  const Domain& domain_;
  double thickness_;
  const Communicator& comm_;
  std::int64_t flips_;
};

}  // namespace rondel
