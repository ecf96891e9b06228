// The periodic cell as a value type (core/Domain.hpp, docs/physics.md section 10): a standing box forms the bits of
// the plain minimum image and wrap; a sheared cell gives a lone disc's image the velocity v + gamma_dot L_y and a
// crossing disc the velocity change -gamma_dot L_y and nothing else; a pair across the sheared boundary has the
// relative position and velocity of the same pair inside the cell; a flip changes no separation; the cell deforms
// as h += dt L h; the plain minimum image refuses a cell that tilts or moves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>

#include "core/Domain.hpp"

namespace rondel {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(Vec2 a, Vec2 b) { return same_bits(a.x, b.x) && same_bits(a.y, b.y); }

Domain box(bool px, bool py) {
  Domain d;
  d.xlo = -0.013, d.xhi = 0.041, d.ylo = 0.002, d.yhi = 0.037;
  d.periodic_x = px, d.periodic_y = py;
  return d;
}

// A cell sheared at gamma_dot (L_xy), its tilt at `tilt`.
Domain sheared(double gamma_dot, double tilt) {
  Domain d = box(true, true);
  d.tilt = tilt;
  d.L.xy = gamma_dot;
  d.rates();
  return d;
}

TEST(Cell, AStandingBoxFormsThePlainMinimumImageAndWrap) {
  std::mt19937_64 rng(5);
  for (const auto& [px, py] : {std::pair{true, true}, {true, false}, {false, true}, {false, false}}) {
    const Domain d = box(px, py);
    const MinimumImage image(d);
    std::uniform_real_distribution<double> u(-0.02, 0.05);
    for (int k = 0; k < 20000; ++k) {
      const Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
      // The reference: x then y, each its own correction (the code before the cell).
      Vec2 ref = b - a;
      if (px && ref.x > 0.5 * d.length_x()) ref.x -= d.length_x();
      if (px && ref.x < -0.5 * d.length_x()) ref.x += d.length_x();
      if (py && ref.y > 0.5 * d.length_y()) ref.y -= d.length_y();
      if (py && ref.y < -0.5 * d.length_y()) ref.y += d.length_y();
      ASSERT_TRUE(same_bits(image.separation(a, b), ref));
      ASSERT_TRUE(same_bits(d.separation(a, b), ref));
      Vec2 x = a, v{0.3, -0.2}, wx = a;
      if (px && wx.x >= d.xhi) wx.x -= d.length_x();
      if (px && wx.x < d.xlo) wx.x += d.length_x();
      if (py && wx.y >= d.yhi) wx.y -= d.length_y();
      if (py && wx.y < d.ylo) wx.y += d.length_y();
      d.wrap(x, v);
      ASSERT_TRUE(same_bits(x, wx));
      ASSERT_TRUE(same_bits(v, Vec2{0.3, -0.2}));  // a standing cell never touches a velocity
    }
  }
}

TEST(Cell, ALoneDiscAndItsImageInAShearedCell) {
  const double gamma_dot = 3.0;
  const Domain d = sheared(gamma_dot, 0.004);
  const double Ly = d.length_y();
  EXPECT_EQ(d.vb.x, gamma_dot * Ly);  // db/dt = L b: the top moves at gamma_dot L_y
  EXPECT_EQ(d.vb.y, 0.0);
  EXPECT_EQ(d.va.x, 0.0);
  // A disc near the top with the affine velocity of its height, seen from a point near the bottom: the image
  // below it (d -= b) moves at v - gamma_dot L_y; seen from the top, the image of a bottom disc at v + gamma_dot L_y.
  const Vec2 top{0.01, d.yhi - 0.001}, bottom{0.012, d.ylo + 0.001};
  const Vec2 v_top{gamma_dot * (top.y - d.ylo), 0.1};
  const Vec2 v_bottom{gamma_dot * (bottom.y - d.ylo), -0.1};
  Vec2 dv;
  ShearedImage(d).separation(bottom, top, dv);
  Vec2 image_v = v_top + dv;
  EXPECT_EQ(image_v.x, v_top.x - gamma_dot * Ly);
  EXPECT_EQ(image_v.y, v_top.y);
  dv = {};
  ShearedImage(d).separation(top, bottom, dv);
  image_v = v_bottom + dv;
  EXPECT_EQ(image_v.x, v_bottom.x + gamma_dot * Ly);
  EXPECT_EQ(image_v.y, v_bottom.y);
  // Crossing the top: the position goes down by b, the velocity by gamma_dot L_y, nothing else.
  Vec2 x{0.02, d.yhi + 1e-5}, v{0.7, 0.25};
  d.wrap(x, v);
  EXPECT_EQ(x.y, (d.yhi + 1e-5) - Ly);
  EXPECT_EQ(x.x, 0.02 - d.tilt);
  EXPECT_EQ(v.x, 0.7 - gamma_dot * Ly);
  EXPECT_EQ(v.y, 0.25);
}

TEST(Cell, APairAcrossTheShearedBoundaryIsThePairInside) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double tilt : {0.0, 0.009, -0.02, 0.027}) {
    const double gamma_dot = -1.7;
    const Domain d = sheared(gamma_dot, tilt);
    const ShearedImage image(d);
    for (int k = 0; k < 2000; ++k) {
      // Disc 1 inside the cell near a side or a corner, disc 2 at r from it (|r| below a tenth of the cell), both
      // with the affine velocity of where they are plus a fluctuation; disc 2 then wrapped into the cell, its
      // velocity with it. Its image seen from disc 1 is where it was, with the velocity it had.
      const double fx = u(rng) < 0.5 ? 0.02 * u(rng) : 1.0 - 0.02 * u(rng);
      const double fy = u(rng) < 0.5 ? 0.02 * u(rng) : 1.0 - 0.02 * u(rng);
      const double y1 = d.ylo + d.length_y() * fy;
      const Vec2 x1{d.xlo + d.shear_shift(y1) + d.length_x() * fx, y1};
      ASSERT_TRUE(d.contains(x1));
      const Vec2 r{0.004 * (2 * u(rng) - 1), 0.004 * (2 * u(rng) - 1)};
      const Vec2 x2 = x1 + r, v2_true = d.flow(x2) + Vec2{-0.03, 0.05};
      Vec2 p2 = x2, v2 = v2_true;
      d.wrap(p2, v2);
      ASSERT_TRUE(d.contains(p2));
      Vec2 dv;
      const Vec2 sep = image.separation(x1, p2, dv);
      const Vec2 image_v = v2 + dv;
      ASSERT_NEAR(sep.x, r.x, 1e-15) << "tilt " << tilt;
      ASSERT_NEAR(sep.y, r.y, 1e-15);
      ASSERT_NEAR(image_v.x, v2_true.x, 1e-12);
      ASSERT_NEAR(image_v.y, v2_true.y, 1e-12);
    }
  }
}

TEST(Cell, AFlipChangesNoSeparation) {
  Domain d = sheared(2.0, 0.5 * 0.054 - 1e-6);
  d.tilt += 2e-6;  // past L_x / 2
  const Domain past = d;
  ASSERT_TRUE(d.flip());
  EXPECT_NEAR(d.tilt, past.tilt - d.length_x(), 1e-18);
  EXPECT_FALSE(d.flip());
  EXPECT_EQ(d.vb.x, past.vb.x);  // the rates are the gradient's: unchanged
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 5000; ++k) {
    const Vec2 x1{d.xlo + d.length_x() * u(rng), d.ylo + d.length_y() * u(rng)};
    const Vec2 r{0.005 * (2 * u(rng) - 1), 0.005 * (2 * u(rng) - 1)};
    Vec2 a = x1, b = x1 + r, a2 = x1, b2 = x1 + r;
    past.wrap(a);
    past.wrap(b);
    d.wrap(a2);  // the same points, labelled in the flipped cell
    d.wrap(b2);
    const Vec2 s_past = ShearedImage(past).separation(a, b), s_flipped = ShearedImage(d).separation(a2, b2);
    ASSERT_NEAR(s_past.x, r.x, 1e-15);
    ASSERT_NEAR(s_flipped.x, r.x, 1e-15);
    ASSERT_NEAR(s_flipped.y, r.y, 1e-15);
  }
}

TEST(Cell, TheCellDeformsByItsGradient) {
  // dh/dt = L h stepped as h += dt L h (the corner fixed): L_x = L_x0 e^(0.2 t), L_y = L_y0 e^(-0.1 t) and
  // d(tilt)/dt = 0.2 tilt + 1.5 L_y, to first order in dt (the error halves with dt); simple shear alone
  // (L_xy only) is exact: tilt = gamma_dot L_y t.
  const auto error = [](double dt) {
    Domain d = box(true, true);
    d.L = {0.2, 1.5, -0.1};
    d.rates();
    const double Lx0 = d.length_x(), Ly0 = d.length_y();
    const int n = static_cast<int>(std::lround(0.1 / dt));
    for (int k = 0; k < n; ++k) d.deform(dt);
    EXPECT_EQ(d.xlo, -0.013);  // the corner stays
    EXPECT_EQ(d.ylo, 0.002);
    const double t = 0.1, tilt = 1.5 * Ly0 * (std::exp(0.2 * t) - std::exp(-0.1 * t)) / 0.3;
    return std::fabs(d.length_x() - Lx0 * std::exp(0.2 * t)) + std::fabs(d.length_y() - Ly0 * std::exp(-0.1 * t)) +
           std::fabs(d.tilt - tilt);
  };
  const double e1 = error(1e-4), e2 = error(5e-5);
  EXPECT_LT(e1, 1e-6);
  EXPECT_NEAR(e1 / e2, 2.0, 0.05);
  Domain shear = box(true, true);
  shear.L.xy = 2.5;
  shear.rates();
  for (int k = 0; k < 4000; ++k) shear.deform(2.5e-5);
  EXPECT_NEAR(shear.tilt, 2.5 * shear.length_y() * 0.1, 1e-15);
  EXPECT_EQ(shear.length_y(), box(true, true).length_y());
}

TEST(Cell, ThePlainMinimumImageRefusesACellThatTiltsOrMoves) {
  EXPECT_THROW(MinimumImage(sheared(1.0, 0.0)), std::logic_error);
  Domain tilted = box(true, true);
  tilted.tilt = 0.001;
  EXPECT_THROW(MinimumImage{tilted}, std::logic_error);
  EXPECT_NO_THROW(MinimumImage(box(true, true)));
}

}  // namespace
}  // namespace rondel
