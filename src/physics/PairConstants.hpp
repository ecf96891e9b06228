#pragma once
// The constants each contact-parameter entry derives from its inputs at set-up (docs/physics.md sections 2,
// 6, 7 and 11): the linear damping ratio from a restitution coefficient, Walton-Braun's unloading stiffness
// K2 = K1/e^2, and the Hertz-Mindlin pair constants
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  1/G* = 2(2 - nu1)(1 + nu1)/E1 + 2(2 - nu2)(1 + nu2)/E2,
//   beta = ln e/sqrt(ln^2 e + pi^2),
// mixed from the two materials of every pair (a wall: its own material), whatever the pair blocks say.
#include <vector>

#include "core/ContactParams.hpp"
#include "core/Material.hpp"

namespace rondel {

double effective_modulus(const Material& a, const Material& b);        // E*
double effective_shear_modulus(const Material& a, const Material& b);  // G*
double tsuji_beta(double e);                                           // beta(e), <= 0

// Fills zeta_n (from e_n, when given), E*, G* and beta, and walton_braun's K2 (from e_wb, when given) of every
// disc-disc and disc-wall entry. Throws ConfigError naming the pair for a K2 below its K1.
void resolve_pair_constants(ContactParamTable& params, const std::vector<Material>& materials);

}  // namespace rondel
