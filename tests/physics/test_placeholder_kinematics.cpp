#include <gtest/gtest.h>

#include "physics/ContactKinematics.hpp"

namespace rondel {
TEST(KinematicsSmoke, RigidRotationHasNoSliding) {
  // Two touching discs rotating rigidly at Omega about disc 1's centre: V_s = 0 with contact-point levers.
  const double R1 = 0.01, R2 = 0.1, u = 1e-5, W = 5.0;
  const double dist = R1 + R2 - u;
  const Vec2 d{dist, 0.0};
  const auto k = disc_disc_kinematics(d, dist, R1, R2, {0, 0}, {0, W * dist}, W, W);
  EXPECT_NEAR(k.V_s, 0.0, 1e-12);
  EXPECT_NEAR(k.V_r, 0.0, 1e-12);
}
}  // namespace rondel
