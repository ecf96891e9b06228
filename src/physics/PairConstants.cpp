#include "physics/PairConstants.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/Errors.hpp"
#include "core/Format.hpp"
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

// `what`: the pair as a message names it ("materials A and B", "material A at walls of material B").
void resolve(ContactParams& p, const Material& a, const Material& b, const std::string& what) {
  if (p.e_n > 0.0) p.zeta_n = zeta_from_restitution(p.e_n), p.beta = tsuji_beta(p.e_n);
  if (p.e_wb > 0.0) p.k_unload = p.k_n / (p.e_wb * p.e_wb);
  if (p.k_unload >= 0.0 && !(p.k_unload >= p.k_n))
    throw ConfigError("walton_braun.K2 = " + fmt(p.k_unload) + " N/m for " + what + " is below its K1 = " + fmt(p.k_n) +
                      " N/m: the unloading stiffness must be at least the loading one (e = sqrt(K1/K2) in (0, 1])");
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
      resolve(params.pair(a, b), materials[a], materials[b],
              "materials " + materials[a].name + " and " + materials[b].name);
      resolve(params.wall(a, b), materials[a], materials[b],
              "material " + materials[a].name + " at walls of material " + materials[b].name);
    }
}

}  // namespace rondel
