#pragma once
// Linear spring-dashpot without tension (docs/validation.md section 4):
//   zeta < 1: e = exp(-zeta arccos(2 zeta^2 - 1)/sqrt(1 - zeta^2)),  t_c = arccos(2 zeta^2 - 1)/w_d
//   zeta > 1: e = exp(-zeta arccosh(2 zeta^2 - 1)/sqrt(zeta^2 - 1))
// with w0 = sqrt(k_n/m_eff), w_d = w0 sqrt(1 - zeta^2). e(0) = 1, t_c(0) = pi/w0.
namespace rondel {

double restitution_from_zeta(double zeta);
// Inverse of restitution_from_zeta for e in (0, 1] (bisection; e decreases monotonically with zeta).
double zeta_from_restitution(double e);
// Contact duration for zeta < 1.
double contact_time(double zeta, double w0);

}  // namespace rondel
