#pragma once
// The parallel bonds' rows (docs/physics.md section 12): their creation at set-up, their pass after the contact
// kernel, their stored energy and their local indices after a rebuild. The law of one bond is BondParallel.hpp.
//
// A bond is a row of a table of its own (ContactTable::bond_table(): key, i1, i2, param and the history Fb_n, Fb_s,
// Mb), keyed like its contact and kept whatever its discs' distance until it breaks. It lives on every rank that owns
// one of its discs (as a border contact does), travels with its discs, and its partner is a ghost there; both ranks
// compute it alike. The pass runs after the contact kernel, in ascending key order, so each disc's sum is: the body
// force, its contacts in ascending partner gid, its walls, then its bonds in ascending partner gid (the same on any
// rank count). On disc 1 a bond adds Fb_n n + Fb_s t and the torque a1 Fb_s + Mb, on disc 2 the opposite force and
// a2 Fb_s - Mb (a_i the kinematics' levers): the work rate of its forces on the pair's relative motion is
// -Fb_n v_n + Fb_s V_s + Mb thetadot_r, integrated as the kernel's terms with the trapezoid of last and this step's
// state (W_b). For the linear springs of a bond that trapezoid is minus the change of its stored energy, so W_b
// and E_stored balance to round-off. A bond that reaches a strength this step breaks: it exerts nothing from this
// step on, its row is removed, and what it held, its stored energy at the start of the step less its last half
// step's work, is booked as E_b_break. A row is booked and a break recorded by the rank that owns its disc 1.
#include <cstdint>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ForceAssembly.hpp"
#include "physics/BondParallel.hpp"
#include "physics/ContactPass.hpp"

namespace rondel {

// A break: the bond, its centre (x1 + a1 n: halfway across the gap), its mode and the stresses that broke it.
struct BondBreak {
  ContactKey key;
  Vec2 position;
  BondMode mode = BondMode::tension;
  double sigma = 0.0, tau = 0.0;
  std::int64_t step = 0;  // the step it broke in
};

// What a bond pass reads (standing domains: bonds are refused in a deforming cell).
struct BondContext {
  const DiscStore& discs;
  const Domain& domain;
  const ContactParamTable& params;
  double thickness;
  double dt;
  std::int64_t step = 0;  // the step being taken (its breaks are recorded with it)
};

namespace bonds {

// A bond row for every pair row of `pairs` (candidates: within the interaction range and skin) whose materials are
// bonded (kb_n > 0) and whose gap |d| - R1 - R2 is at most gap x min(R1, R2); two discs of one rigid body are not
// bonded. `bonds` gets them in key order.
void create(const DiscStore& discs, const Domain& domain, const ContactParamTable& params, const ContactTable& pairs,
            double gap, ContactTable& bonds);

// One step of every bond: its state, its forces into the sums, its breaks (removed from the table and appended to
// `breaks` when booked here) and its ledger terms into `work` (W_b, E_b_break).
void step(const BondContext& c, ContactTable& bonds, ForceSums sums, LedgerTerms& work, std::vector<BondBreak>& breaks);

// The bonds' forces as they stand, into the sums (the initial forces: no update, nothing booked).
void apply(const BondContext& c, const ContactTable& bonds, ForceSums sums);

// The section of bond row r (its discs' radii, its pair's lambda, the discs' thickness).
BondGeometry row_geometry(const BondContext& c, const ContactTable& bonds, std::size_t r);

// The bonds this rank books (its disc 1 owned here).
std::int64_t booked(const DiscStore& discs, const ContactTable& bonds);

// The energy the booked bonds store [J per thickness].
double stored(const BondContext& c, const ContactTable& bonds);

// After a rebuild (the discs migrated, the ghosts built): each row's local indices from its gids, rows with no owned
// disc dropped. Returns false when a row's other disc is not on this rank (its bond has stretched beyond the ghosts'
// reach), the first such key in `lost`.
bool relink(const DiscStore& discs, ContactTable& bonds, ContactKey& lost);

}  // namespace bonds
}  // namespace rondel
