// Restitution and damping ratio (docs/validation.md section 4), and the inverse used for `linear.e`.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/Restitution.hpp"

namespace rondel {
namespace {

TEST(Restitution, UndampedIsElasticWithHalfPeriodContact) {
  EXPECT_EQ(restitution_from_zeta(0.0), 1.0);
  EXPECT_NEAR(contact_time(0.0, 2.0), std::numbers::pi / 2.0, 1e-14);
}

TEST(Restitution, InverseRecoversZetaOnBothBranches) {
  for (double zeta : {0.05, 0.1, 0.3, 0.5, 0.7, 0.99, 1.5, 3.0}) {
    const double e = restitution_from_zeta(zeta);
    EXPECT_GT(e, 0.0);
    EXPECT_LT(e, 1.0);
    EXPECT_NEAR(zeta_from_restitution(e), zeta, 1e-9 * (1 + zeta)) << "zeta " << zeta;
  }
}

TEST(Restitution, DecreasesWithDamping) {
  double last = 1.0;
  for (double zeta = 0.05; zeta < 4.0; zeta += 0.05) {
    const double e = restitution_from_zeta(zeta);
    EXPECT_LT(e, last) << zeta;
    last = e;
  }
}

}  // namespace
}  // namespace rondel
