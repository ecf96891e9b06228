#include "physics/PairConstants.hpp"

#include <cmath>
#include <numbers>

#include "physics/Restitution.hpp"

namespace rondel {

double effective_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

double effective_shear_modulus(const Material& a, const Material& b) {
  return 1.0 / (2.0 * (2.0 - a.poisson_ratio) * (1.0 + a.poisson_ratio) / a.youngs_modulus +
                2.0 * (2.0 - b.poisson_ratio) * (1.0 + b.poisson_ratio) / b.youngs_modulus);
}

double tsuji_beta(double e) {
  const double l = std::log(e);
  return l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

namespace {

void resolve(ContactParams& p, const Material& a, const Material& b) {
  if (p.e_n > 0.0) p.zeta_n = zeta_from_restitution(p.e_n), p.beta = tsuji_beta(p.e_n);
  if (a.youngs_modulus > 0.0 && b.youngs_modulus > 0.0) {
    p.E_star = effective_modulus(a, b);
    p.G_star = effective_shear_modulus(a, b);
  }
}

}  // namespace

void resolve_pair_constants(ContactParamTable& params, const std::vector<Material>& materials) {
  const std::size_t n = params.n_materials();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      resolve(params.pair(a, b), materials[a], materials[b]);
      resolve(params.wall(a, b), materials[a], materials[b]);
    }
}

}  // namespace rondel
