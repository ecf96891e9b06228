#include "physics/Restitution.hpp"

#include <cmath>

namespace rondel {

double restitution_from_zeta(double zeta) {
  if (zeta <= 0.0) return 1.0;
  const double c = 2.0 * zeta * zeta - 1.0;
  if (zeta < 1.0) return std::exp(-zeta * std::acos(c) / std::sqrt(1.0 - zeta * zeta));
  if (zeta == 1.0) return std::exp(-2.0);  // the limit of both branches
  return std::exp(-zeta * std::acosh(c) / std::sqrt(zeta * zeta - 1.0));
}

double zeta_from_restitution(double e) {
  if (e >= 1.0) return 0.0;
  double lo = 0.0, hi = 1.0;
  while (restitution_from_zeta(hi) > e) hi *= 2.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (restitution_from_zeta(mid) > e)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

double contact_time(double zeta, double w0) {
  const double c = 2.0 * zeta * zeta - 1.0;
  return std::acos(c) / (w0 * std::sqrt(1.0 - zeta * zeta));
}

}  // namespace rondel
