#include "physics/BondPass.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rondel::bonds {

namespace {

// The kinematics of bond row r (its discs' positions by the minimum image, their half-step velocities).
ContactKinematics row_kinematics(const DiscStore& D, const MinimumImage& image, const ContactTable& t, std::size_t r) {
  const auto i = static_cast<std::size_t>(t.i1[r]), j = static_cast<std::size_t>(t.i2[r]);
  const Vec2 d = image.separation(D.position[i], D.position[j]);
  return disc_disc_kinematics(d, std::sqrt(dot(d, d)), D.radius[i], D.radius[j], D.velocity[i], D.velocity[j],
                              D.omega[i], D.omega[j]);
}

BondState row_state(const ContactTable& t, std::size_t r) { return {t.slot[0][r], t.slot[1][r], t.slot[2][r]}; }

// The work rate of a bond's forces on its pair's relative motion, times dt.
double work(const BondState& s, const ContactKinematics& k, double dt) {
  return (-s.Fb_n * k.v_n + s.Fb_s * k.V_s + s.Mb * k.thetadot_r) * dt;
}

// The bond's terms of its discs' sums (see the header).
void add_to_sums(const ContactTable& t, std::size_t r, const ContactKinematics& k, const BondState& s, ForceSums sums) {
  const auto i = static_cast<std::size_t>(t.i1[r]), j = static_cast<std::size_t>(t.i2[r]);
  const Vec2 f1 = s.Fb_n * k.n + s.Fb_s * k.t;
  sums.force[i] += f1;
  sums.torque[i] += k.a1 * s.Fb_s + s.Mb;
  sums.force[j] -= f1;
  sums.torque[j] += k.a2 * s.Fb_s - s.Mb;
}

}  // namespace

BondGeometry row_geometry(const BondContext& c, const ContactTable& t, std::size_t r) {
  const auto i = static_cast<std::size_t>(t.i1[r]), j = static_cast<std::size_t>(t.i2[r]);
  const ContactParams& p = c.params.pairs()[static_cast<std::size_t>(t.param[r])];
  return BondGeometry::of(c.discs.radius[i], c.discs.radius[j], c.thickness, p.bond_lambda);
}

void create(const DiscStore& discs, const Domain& domain, const ContactParamTable& params, const ContactTable& pairs,
            double gap, ContactTable& bonds) {
  const MinimumImage image(domain);
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    const auto i = static_cast<std::size_t>(pairs.i1[r]), j = static_cast<std::size_t>(pairs.i2[r]);
    if (!(params.pairs()[static_cast<std::size_t>(pairs.param[r])].kb_n > 0.0)) continue;
    if (same_rigid_body(discs.flags[i], discs.flags[j])) continue;
    const Vec2 d = image.separation(discs.position[i], discs.position[j]);
    const double R1 = discs.radius[i], R2 = discs.radius[j];
    if (std::sqrt(dot(d, d)) - R1 - R2 <= gap * std::min(R1, R2))
      bonds.push(pairs.key[r], pairs.i1[r], pairs.i2[r], pairs.param[r]);
  }
}

void step(const BondContext& c, ContactTable& t, ForceSums sums, LedgerTerms& work_terms,
          std::vector<BondBreak>& breaks) {
  const MinimumImage image(c.domain);
  const std::size_t n_owned = c.discs.n_owned();
  std::vector<bool> broken;
  double W = 0.0, released = 0.0, tension = 0.0, shear = 0.0;
  for (std::size_t r = 0; r < t.size(); ++r) {
    const ContactKinematics k = row_kinematics(c.discs, image, t, r);
    const BondGeometry g = row_geometry(c, t, r);
    const ContactParams& p = c.params.pairs()[static_cast<std::size_t>(t.param[r])];
    const BondState before = row_state(t, r);
    const BondStrengths strength = BondStrengths::of(p, t.key[r].lo, t.key[r].hi);
    const BondStep s = bond_step(p, g, k, c.dt, before, strength.sigma_c, strength.tau_c);
    const bool book = static_cast<std::size_t>(t.i1[r]) < n_owned;
    if (s.mode != BondMode::intact) {
      if (broken.empty()) broken.assign(t.size(), false);
      broken[r] = true;
      if (!book) continue;
      const double last_half = 0.5 * work(before, k, c.dt);
      W += last_half;
      released += bond_stored(p, g, before) - last_half;
      const Vec2 centre = c.discs.position[static_cast<std::size_t>(t.i1[r])] + k.a1 * k.n;
      breaks.push_back({t.key[r], centre, s.mode, s.sigma, s.tau, c.step});
      (s.mode == BondMode::tension ? tension : shear) += 1.0;
      continue;
    }
    t.slot[0][r] = s.state.Fb_n, t.slot[1][r] = s.state.Fb_s, t.slot[2][r] = s.state.Mb;
    add_to_sums(t, r, k, s.state, sums);
    if (book) W += 0.5 * (work(before, k, c.dt) + work(s.state, k, c.dt));
  }
  work_terms.W_b += W;
  work_terms.E_b_break += released;
  work_terms.n_b_tension += tension;
  work_terms.n_b_shear += shear;
  if (broken.empty()) return;
  ContactTable kept = t.empty_like();
  for (std::size_t r = 0; r < t.size(); ++r)
    if (!broken[r]) {
      kept.push_copy(t, r);
      kept.i1.back() = t.i1[r], kept.i2.back() = t.i2[r];
    }
  t = std::move(kept);
}

void apply(const BondContext& c, const ContactTable& t, ForceSums sums) {
  const MinimumImage image(c.domain);
  for (std::size_t r = 0; r < t.size(); ++r)
    add_to_sums(t, r, row_kinematics(c.discs, image, t, r), row_state(t, r), sums);
}

std::int64_t booked(const DiscStore& discs, const ContactTable& t) {
  return std::count_if(t.i1.begin(), t.i1.end(),
                       [n = discs.n_owned()](std::int32_t i) { return static_cast<std::size_t>(i) < n; });
}

double stored(const BondContext& c, const ContactTable& t) {
  double e = 0.0;
  for (std::size_t r = 0; r < t.size(); ++r)
    if (static_cast<std::size_t>(t.i1[r]) < c.discs.n_owned())
      e += bond_stored(c.params.pairs()[static_cast<std::size_t>(t.param[r])], row_geometry(c, t, r), row_state(t, r));
  return e;
}

bool relink(const DiscStore& discs, ContactTable& t, ContactKey& lost) {
  std::vector<std::pair<std::int64_t, std::int32_t>> index(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i) index[i] = {discs.gid[i], static_cast<std::int32_t>(i)};
  std::sort(index.begin(), index.end());  // a disc is on a rank once (owned or a ghost)
  const auto find = [&index](std::int64_t gid) {
    const auto it = std::lower_bound(index.begin(), index.end(), std::make_pair(gid, std::int32_t{-1}));
    return it != index.end() && it->first == gid ? it->second : std::int32_t{-1};
  };
  const auto n_owned = static_cast<std::int32_t>(discs.n_owned());
  bool ok = true;
  ContactTable kept = t.empty_like();
  kept.reserve(t.size());
  for (std::size_t r = 0; r < t.size(); ++r) {
    const std::int32_t i = find(t.key[r].lo), j = find(t.key[r].hi);
    const bool owned_i = i >= 0 && i < n_owned, owned_j = j >= 0 && j < n_owned;
    if (!owned_i && !owned_j) continue;
    if (i < 0 || j < 0) {
      if (ok) lost = t.key[r];
      ok = false;
      continue;
    }
    kept.push_copy(t, r);
    kept.i1.back() = i, kept.i2.back() = j;
  }
  t = std::move(kept);
  return ok;
}

}  // namespace rondel::bonds
