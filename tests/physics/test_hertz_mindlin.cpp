// Hertz-Mindlin contacts and the mixing of materials, docs/validation.md section 9 (docs/physics.md section 6).
// The expected values are the formulas of section 9, evaluated here:
//   E* = 1/((1 - nu1^2)/E1 + (1 - nu2^2)/E2),  G* = 1/(2(2 - nu1)(1 + nu1)/E1 + 2(2 - nu2)(1 + nu2)/E2),
//   u_max = (15 m_eff v0^2/(16 E* sqrt(R*)))^(2/5),  t_c = 2 u_max/v0 sqrt(pi) Gamma(7/5)/Gamma(9/10);
// the damped restitution against an RK4 integration of the same one-dimensional force law at t_c/10^4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "physics/CriticalTimeStep.hpp"
#include "physics/NormalHertz.hpp"
#include "physics/OneContactRig.hpp"
#include "physics/PairConstants.hpp"
#include "physics/TangentialMindlin.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

constexpr double kR = test::d5::R;
const LawSelection kHertzOnly{"hertz", "none", "none"};

Material glass() {
  Material m;
  m.name = "glass";
  m.density = test::d5::density;
  m.youngs_modulus = 7e10;
  m.poisson_ratio = 0.25;
  return m;
}
Material steel() {
  Material m = glass();
  m.name = "steel";
  m.density = 7800.0;
  m.youngs_modulus = 2e11;
  m.poisson_ratio = 0.3;
  return m;
}

ContactParams hertz_params(const Material& a, const Material& b, double e) {
  ContactParams p;
  p.e_n = e;
  p.mu = 0.5;
  ContactParamTable t(2);
  t.pair(0, 1) = p;
  resolve_pair_constants(t, {a, b});
  return t.pair(0, 1);
}

double u_max_formula(double m_eff, double E_star, double R_star, double v0) {
  return std::pow(15.0 * m_eff * v0 * v0 / (16.0 * E_star * std::sqrt(R_star)), 0.4);
}
double t_c_formula(double u_max, double v0) {
  return 2.0 * u_max / v0 * std::sqrt(std::numbers::pi) * std::tgamma(1.4) / std::tgamma(0.9);
}

struct Impact {
  double u_max = 0.0, t_c = 0.0, e = 0.0, energy_drift = 0.0;
};

// A head-on impact at v0 (disc 1 towards disc 2 or the wall), integrated by the library's kernel. The
// largest overlap is the vertex of the parabola through the three samples around the largest one; the
// contact time runs between the overlap's zero crossings, interpolated linearly.
Impact impact(const ContactParams& p, double R2, double v0, double dt, double density = test::d5::density) {
  const double gap = 0.25 * v0 * dt;  // the onset inside a step
  testing_rig::OneContactRig rig({"hertz", "none", "none"}, p, kR, R2, -gap, 0.0, {}, density);
  const bool wall = std::isinf(R2);
  rig.discs().velocity[0] = (wall ? v0 : 0.5 * v0) * rig.n;
  if (!wall) rig.discs().velocity[1] = -0.5 * v0 * rig.n;
  rig.start(dt);
  const double E0 = rig.energy();
  std::vector<double> u{rig.overlap()};
  Impact out;
  for (int s = 0; s < 100000; ++s) {
    rig.step();
    u.push_back(rig.overlap());
    out.energy_drift = std::max(out.energy_drift, std::fabs(rig.energy() - E0) / E0);
    if (u.size() > 3 && u.back() < 0.0 && u[u.size() - 2] < 0.0 && *std::max_element(u.begin(), u.end()) > 0.0) break;
  }
  const auto k = static_cast<std::size_t>(std::max_element(u.begin(), u.end()) - u.begin());
  const double a = u[k - 1], b = u[k], c = u[k + 1];
  out.u_max = b + (a - c) * (a - c) / (8.0 * (2.0 * b - a - c));  // parabola vertex
  double t_in = -1.0, t_out = -1.0;
  for (std::size_t s = 1; s < u.size(); ++s) {
    const double x = u[s - 1] / (u[s - 1] - u[s]);
    if (u[s - 1] < 0.0 && u[s] >= 0.0 && t_in < 0.0) t_in = dt * (static_cast<double>(s - 1) + x);
    if (u[s - 1] >= 0.0 && u[s] < 0.0) t_out = dt * (static_cast<double>(s - 1) + x);
  }
  out.t_c = t_out - t_in;
  out.e = rig.normal_velocity() / v0;
  return out;
}

TEST(HertzMindlin, MixedModuliOfUnlikeMaterials) {
  const double E_star = 1.0 / ((1 - 0.0625) / 7e10 + (1 - 0.09) / 2e11);
  const double G_star = 1.0 / (2 * 1.75 * 1.25 / 7e10 + 2 * 1.7 * 1.3 / 2e11);
  EXPECT_NEAR(effective_modulus(glass(), steel()), E_star, 1e-12 * E_star);
  EXPECT_NEAR(effective_shear_modulus(glass(), steel()), G_star, 1e-12 * G_star);
  EXPECT_NEAR(effective_modulus(glass(), glass()), 7e10 / (2 * (1 - 0.0625)), 1e-12 * 3.7e10) << "3.7333333e10 Pa";
  EXPECT_NEAR(effective_shear_modulus(glass(), glass()), 8.0e9, 1e-6 * 8.0e9) << "G* = 8.0e9 Pa";
  const ContactParams p = hertz_params(glass(), steel(), 0.5);
  EXPECT_EQ(p.E_star, effective_modulus(glass(), steel())) << "the pair entry holds the mixed constants";
  const double l = std::log(0.5);
  EXPECT_NEAR(p.beta, l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi), 1e-15);
}

TEST(HertzMindlin, UndampedImpactOfTwoDiscs) {
  const ContactParams p = hertz_params(glass(), glass(), 1.0);
  const double m_eff = 0.5 * test::d5::mass(), R_star = 0.5 * kR, v0 = 1.0;
  const double u_max = u_max_formula(m_eff, p.E_star, R_star, v0), t_c = t_c_formula(u_max, v0);
  EXPECT_NEAR(u_max, 7.7140794e-5, 1e-12) << "docs/validation.md section 9";
  EXPECT_NEAR(t_c, 2.2704653e-4, 1e-10);
  const Impact r = impact(p, kR, v0, t_c / 100.0);
  std::printf("[Hertz impact, dt = t_c/100] u_max %.8g (exact %.8g), t_c %.8g (exact %.8g), e %.8f, drift %.2e\n",
              r.u_max, u_max, r.t_c, t_c, r.e, r.energy_drift);
  EXPECT_NEAR(r.u_max, u_max, 1e-3 * u_max);
  EXPECT_NEAR(r.t_c, t_c, 1e-3 * t_c);
  EXPECT_NEAR(r.e, 1.0, 1e-4);
  EXPECT_LT(r.energy_drift, 1e-3) << "kinetic + stored 8/15 E* sqrt(R*) u^(5/2) is conserved";
}

TEST(HertzMindlin, UndampedImpactOnAWallOfTheSameMaterial) {
  const ContactParams p = hertz_params(glass(), glass(), 1.0);
  const double m = test::d5::mass(), v0 = 1.0;
  const double u_max = u_max_formula(m, p.E_star, kR, v0), t_c = t_c_formula(u_max, v0);
  EXPECT_NEAR(u_max, 8.8611503e-5, 1e-12);
  const Impact r = impact(p, INFINITY, v0, t_c / 100.0);
  EXPECT_NEAR(r.u_max, u_max, 1e-3 * u_max);
  EXPECT_NEAR(r.t_c, t_c, 1e-3 * t_c);
  EXPECT_NEAR(r.e, 1.0, 1e-4);
}

// The one-dimensional Hertz-Tsuji contact, m_eff u'' = -max(0, 2/3 S u + c u'), S = 2 E* sqrt(R* u),
// c = -2 sqrt(5/6) beta sqrt(S m_eff), from u = 0 at u' = v0 until it separates: RK4 at t_c/10^4.
double restitution_rk4(const ContactParams& p, double m_eff, double R_star, double v0) {
  const double t_c = t_c_formula(u_max_formula(m_eff, p.E_star, R_star, v0), v0), h = t_c / 1e4;
  auto accel = [&](double u, double w) {
    if (u <= 0.0) return 0.0;
    const double S = 2.0 * p.E_star * std::sqrt(R_star * u);
    const double c = -NormalHertz::kDashpot * p.beta * std::sqrt(S * m_eff);
    return -std::max(0.0, 2.0 / 3.0 * S * u + c * w) / m_eff;
  };
  double u = 0.0, w = v0;
  for (int s = 0; s < 10000000 && !(s > 10 && u <= 0.0); ++s) {
    const double k1u = w, k1w = accel(u, w);
    const double k2u = w + 0.5 * h * k1w, k2w = accel(u + 0.5 * h * k1u, w + 0.5 * h * k1w);
    const double k3u = w + 0.5 * h * k2w, k3w = accel(u + 0.5 * h * k2u, w + 0.5 * h * k2w);
    const double k4u = w + h * k3w, k4w = accel(u + h * k3u, w + h * k3w);
    u += h / 6.0 * (k1u + 2 * k2u + 2 * k3u + k4u);
    w += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return -w / v0;
}

TEST(HertzMindlin, DampedRestitutionMatchesTheForceLawAndIsIndependentOfSpeed) {
  const ContactParams p = hertz_params(glass(), glass(), 0.5);
  const double m_eff = 0.5 * test::d5::mass(), R_star = 0.5 * kR;
  std::vector<double> e;
  for (double v0 : {0.1, 1.0, 10.0}) {
    SCOPED_TRACE(v0);
    const double t_c = t_c_formula(u_max_formula(m_eff, p.E_star, R_star, v0), v0);
    const double reference = restitution_rk4(p, m_eff, R_star, v0);
    const Impact r = impact(p, kR, v0, t_c / 100.0);
    std::printf("[Hertz damped, e = 0.5, v0 = %g] code %.6f, RK4 %.6f\n", v0, r.e, reference);
    EXPECT_NEAR(r.e, reference, 1e-2);
    e.push_back(r.e);
  }
  EXPECT_NEAR(e[0], e[1], 1e-2);
  EXPECT_NEAR(e[2], e[1], 1e-2);
}

// A light disc (glass) against a heavy one (steel): m_eff from the two masses, E* mixed.
TEST(HertzMindlin, LightAgainstHeavyDiscUsesBothMassesAndTheMixedModulus) {
  const ContactParams p = hertz_params(glass(), steel(), 1.0);
  const double m1 = test::d5::mass(), m2 = 7800.0 * std::numbers::pi * kR * kR;
  const double m_eff = m1 * m2 / (m1 + m2), v0 = 1.0;
  const double u_max = u_max_formula(m_eff, p.E_star, 0.5 * kR, v0), t_c = t_c_formula(u_max, v0);
  // The rig gives both discs one density: give disc 2 its own mass and inertia.
  testing_rig::OneContactRig rig(kHertzOnly, p, kR, kR, -0.25 * v0 * t_c / 100.0, 0.0);
  rig.discs().set_material(1, 1, steel());
  rig.discs().velocity[0] = v0 * rig.n;
  rig.start(t_c / 100.0);
  double u = 0.0;
  for (int s = 0; s < 400; ++s) rig.step(), u = std::max(u, rig.overlap());
  EXPECT_NEAR(u, u_max, 2e-3 * u_max);
  // Momentum: the light disc bounces back with (m1 - m2)/(m1 + m2) v0 at e = 1.
  EXPECT_NEAR(dot(rig.discs().velocity[0], rig.n), (m1 - m2) / (m1 + m2) * v0, 1e-4);
}

TEST(HertzMindlin, MindlinStiffnessBelowTheCapAndTheCappingRule) {
  const ContactParams p = hertz_params(glass(), glass(), 1.0);  // beta = 0: no dashpot
  ContactKinematics k = contact_geometry(kR, kR, false);
  k.u_n = 2e-5;
  k.V_s = 0.01;
  const ContactBodies b =
      disc_disc_bodies(test::d5::mass(), test::d5::mass(), test::d5::inertia(), test::d5::inertia());
  const double S_t = 8.0 * p.G_star * std::sqrt(k.R_star * k.u_n), dt = 1e-7;
  std::vector<double> xi{0.0};
  const TangentialMindlin::History h{xi[0]};
  const double F_n = 1e6;  // a large cap
  const TangentialForce below = TangentialMindlin::force(ContactInput{p, b, k, F_n, dt}, h);
  EXPECT_NEAR(below.F_t, -S_t * k.V_s * dt, 1e-12 * S_t * k.V_s * dt);
  EXPECT_EQ(below.slip, 0.0);
  const double small = 1e-3;  // now above the cap mu F_n
  const TangentialForce above = TangentialMindlin::force(ContactInput{p, b, k, small, dt}, h);
  EXPECT_DOUBLE_EQ(above.F_t, -p.mu * small);
  EXPECT_DOUBLE_EQ(xi[0], -above.F_t / S_t) << "the spring is reset so that it alone gives the cap";
  EXPECT_GT(above.slip, 0.0);
  EXPECT_NEAR(TangentialMindlin::stored(ContactInput{p, b, k}, h), above.F_t * above.F_t / (2.0 * S_t), 1e-20);
}

TEST(HertzMindlin, NormalForceAndStoredEnergyAreTheFormulas) {
  const ContactParams p = hertz_params(glass(), steel(), 1.0);
  ContactKinematics k = contact_geometry(kR, 2 * kR, false);
  k.u_n = 3e-5;
  const ContactBodies b = disc_disc_bodies(1.0, 2.0, 1.0, 1.0);
  const double F = 4.0 / 3.0 * p.E_star * std::sqrt(k.R_star) * std::pow(k.u_n, 1.5);
  EXPECT_NEAR(NormalHertz::force(ContactInput{p, b, k}).F_n, F, 1e-12 * F);
  const double E = 8.0 / 15.0 * p.E_star * std::sqrt(k.R_star) * std::pow(k.u_n, 2.5);
  EXPECT_NEAR(NormalHertz::stored(ContactInput{p, b, k}), E, 1e-12 * E);
}

// The critical step of a stiffening contact: S_n at the largest overlap the run allows.
TEST(HertzMindlin, CriticalStepUsesTheStiffnessAtTheLargestOverlap) {
  const ContactParams p = hertz_params(glass(), glass(), 1.0);
  const double m = test::d5::mass(), u = 0.1 * kR;
  const double S_n = 2.0 * p.E_star * std::sqrt(0.5 * kR * u);
  const ContactBody A{m, test::d5::inertia(), kR};
  std::string mode;
  const double dt = contact_critical_step(kHertzOnly, p, A, A, &mode, 0.1);
  EXPECT_EQ(mode, "normal");
  EXPECT_NEAR(dt, 2.0 / std::sqrt(S_n / (0.5 * m)), 1e-12 * dt);
  // With Mindlin the tangential mode (S_t = 8 G* sqrt(R* u), 1/m_t = 1/m1 + 1/m2 + R^2/I1 + R^2/I2) limits.
  const double S_t = 8.0 * p.G_star * std::sqrt(0.5 * kR * u), m_t = 1.0 / (2.0 / m + 2.0 * kR * kR / A.I);
  const double dt_hm = contact_critical_step({"hertz", "mindlin", "none"}, p, A, A, &mode, 0.1);
  EXPECT_EQ(mode, "tangential");
  EXPECT_NEAR(dt_hm, 2.0 / std::sqrt(S_t / m_t), 1e-12 * dt_hm);
  // The search over two materials reports the limiting pair by name, and the Rayleigh step.
  ContactParamTable t(2);
  for (std::size_t a = 0; a < 2; ++a)
    for (std::size_t c = 0; c < 2; ++c) t.pair(a, c).e_n = 1.0;
  resolve_pair_constants(t, {glass(), steel()});
  std::vector<MaterialInfo> mats{{2650.0, 1.0, kR, kR, Material::Body::disc, 7e10, 0.25, "glass"},
                                 {7800.0, 1.0, 0.5 * kR, 0.5 * kR, Material::Body::disc, 2e11, 0.3, "steel"}};
  const CriticalStep c = critical_time_step(kHertzOnly, t, mats, false, {0.1, {}});
  EXPECT_NE(c.pair.find("material steel R=0.0025 / material steel R=0.0025"), std::string::npos) << c.pair;
  const double G = 2e11 / (2 * 1.3);
  EXPECT_NEAR(c.rayleigh, std::numbers::pi * 0.5 * kR * std::sqrt(7800.0 / G) / (0.1631 * 0.3 + 0.8766), 1e-18);
}

TEST(Materials, SphereBodyMassAndInertia) {
  Material m = glass();
  m.body = Material::Body::sphere;
  const double mass = 4.0 / 3.0 * std::numbers::pi * m.density * kR * kR * kR;
  EXPECT_NEAR(m.mass(kR), mass, 1e-15 * mass);
  EXPECT_NEAR(m.inertia(mass, kR), 0.4 * mass * kR * kR, 1e-25);
  m.body = Material::Body::disc;
  EXPECT_EQ(m.mass(kR), test::d5::mass()) << "a disc body is the cylinder of docs/physics.md section 1, bit for bit";
}

TEST(Materials, TableTextRoundTripsBitForBit) {
  Material s = steel();
  s.body = Material::Body::sphere;
  const std::vector<Material> table{glass(), s};
  EXPECT_EQ(parse_material_table(material_table_text(table)), table);
}

}  // namespace
}  // namespace rondel
