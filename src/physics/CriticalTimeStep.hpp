#pragma once
// Critical time step of velocity Verlet (docs/physics.md section 4): for each contact mode of angular
// frequency w and damping ratio zeta, dt < (2/w)(sqrt(1 + zeta^2) - zeta). Modes:
//   normal                 w^2 = k_n/m_eff
//   tangential (rotation)  w^2 = k_s/m_t,  1/m_t = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2
//   rolling                w^2 = K/I_red,  I_red = I1 I2/(I1 + I2) (a wall: I1), K the rolling stiffness
//                          (each law's spring(), e.g. jiang_*: k_n B^2/12; wang: k_r R*^2; iwashita_oda: K_r)
//   tangential and rolling together: the larger eigenvalue of the coupled 2 x 2 problem in (s, theta_r),
//                          exact in closed form (docs/physics.md's sum bound k_s/m_t + K/I_red is conservative
//                          but only 0.77 of the limit for equal discs at delta = 3)
// A law without an a-priori spring declares `no_spring` instead (displacement_damping's stiffness grows
// with F_n; force_proportional and constant_torque have no spring). dt_crit is the smallest limit over every material
// pair and radius pair that can occur (radii sampled geometrically between the smallest and the largest), walls
// included.
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/Material.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

struct MaterialInfo {
  double density = 0.0;
  double thickness = 1.0;
  double R_min = 0.0;  // smallest and largest radius of this material in the scene (0: no disc of it)
  double R_max = 0.0;
  Material::Body body = Material::Body::disc;
  double youngs_modulus = 0.0, poisson_ratio = 0.0;  // for the Rayleigh step of a Hertz-Mindlin run
  std::string name;                                  // in the report ("" = "material INDEX")
};

// What the search covers besides the materials: the overlap at which a stiffening contact (hertz, mindlin)
// is linearised, as a fraction of the smaller radius (run.max_overlap), and the materials of the walls.
struct CriticalOptions {
  double max_overlap = 0.1;
  std::vector<int> wall_materials{0};
};

struct CriticalStep {
  double dt = 0.0;
  std::string mode;       // "normal", "tangential", "rolling", "tangential+rolling"
  std::string pair;       // which bodies, e.g. "material 0 R=0.005 / material 0 R=0.005" or "... / wall"; a
                          // Hertz-Mindlin run adds the overlap assumed and the Rayleigh step
  double rayleigh = 0.0;  // Hertz-Mindlin: pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smallest disc; else 0
};

// A body of a contact: a disc, or a wall (m = I = R = inf).
struct ContactBody {
  double m, I, R;
};

// Stability limit of one mode.
double mode_limit(double omega, double zeta);

// The critical step of one contact (its most limiting mode); `mode` receives the mode's name. A hertz or
// mindlin contact is linearised at the overlap max_overlap x the smaller radius (docs/physics.md section 6).
// A bonded pair (p.kb_n > 0, `thickness` > 0: the discs' thickness) adds its bond's springs kb_n A, kb_s A and
// kb_n I to the normal, tangential and rolling springs (docs/physics.md section 12); its modes are named "... + bond".
double contact_critical_step(const LawSelection& laws, const ContactParams& p, const ContactBody& a,
                             const ContactBody& b, std::string* mode = nullptr, double max_overlap = 0.1,
                             double thickness = 0.0);

CriticalStep critical_time_step(const LawSelection& laws, const ContactParamTable& params,
                                const std::vector<MaterialInfo>& materials, bool has_walls,
                                const CriticalOptions& options = {});

}  // namespace rondel
