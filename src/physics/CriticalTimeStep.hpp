#pragma once
// Critical time step of velocity Verlet (PHYSICS.md section 4): for each contact mode of angular
// frequency w and damping ratio zeta, dt < (2/w)(sqrt(1 + zeta^2) - zeta). Modes:
//   normal                   w^2 = k_n/m_eff
//   tangential with rotation w^2 = k_s/m_t,  1/m_t = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2
// (rolling modes join with the rolling laws). dt_crit is the smallest limit over every material pair and
// radius pair that can occur, walls included.
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

struct MaterialInfo {
  double density = 0.0;
  double thickness = 1.0;
  double R_min = 0.0;  // smallest and largest radius of this material in the scene
  double R_max = 0.0;
};

struct CriticalStep {
  double dt = 0.0;
  std::string mode;  // "normal", "tangential"
  std::string pair;  // which bodies, e.g. "material 0 R=0.005 / material 0 R=0.005" or "... / wall"
};

// Stability limit of one undamped-or-damped mode.
double mode_limit(double omega, double zeta);

CriticalStep critical_time_step(const LawSelection& laws, const ContactParamTable& params,
                                const std::vector<MaterialInfo>& materials, bool has_walls);

}  // namespace rondel
