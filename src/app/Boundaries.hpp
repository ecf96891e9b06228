#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ExactSum.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/FusedReduction.hpp"

namespace rondel {

// Loads and motions of the walls (docs/design.md section 4, step 2).
//  - measure(): each wall's load from the discs in the last step, summed exactly over ranks, so a servo
//    sees the same force on any rank count;
//  - steer(): velocities of controlled walls. A servo moves along its normal with
//      v_n = clamp(gain (F_target - F) / (max(N_c, 1) (k_n dt + c_n)), +-v_max),  F_target = sigma L t:
//    a wall step v dt changes each contact's force by k_n v dt through the spring and by c_n v at once
//    through the dashpot, so with gain < 1 one step closes at most that fraction of the force error (the
//    dashpot term matters: without it the wall chatters between +-v_max at the dashpot's response);
//    a strain-rate wall moves with v_n = rate x (distance to the opposite box wall); a shear velocity
//    (walls.control 'side:shear:V') adds V along the wall.
//  - box geometry: the sample's width and height between the box walls (for stresses and strains).
struct BoxGeometry {
  double width = 0.0, height = 0.0;
  bool has_x = false, has_y = false;  // left and right walls, bottom and top walls
};

// This rank's part of every wall's load (three exact sums: x, y, normal; and the contact count), to be
// reduced over the ranks in the step's one reduction (FusedReduction).
struct WallLoads {
  std::vector<std::array<ExactSum, 3>> sums;
  std::vector<std::int64_t> counts;
  // Adds the loads to `r`; returns the first slot of each wall (apply() reads them back).
  std::vector<std::array<std::size_t, 4>> add_to(FusedReduction& r) const;
};

class Boundaries {
 public:
  // `k_n`, `c_n`: the stiffest normal spring and the largest normal dashpot coefficient of a contact that
  // loads a wall (the heaviest disc; with rough walls also disc-disc contacts with the glued discs).
  Boundaries(double servo_gain, double servo_max_speed, double k_n = 0.0, double c_n = 0.0)
      : gain_(servo_gain), v_max_(servo_max_speed), k_n_(k_n), c_n_(c_n) {}

  // True when a wall is servo- or strain-rate-controlled or shears (then loads are measured every step).
  static bool controlled(const WallSet& walls);
  static bool any_rough(const WallSet& walls);
  // The walls this object steers: remembers whether any is controlled or rough (after a restart's glue too).
  void bind(const WallSet& walls) { controlled_ = controlled(walls), rough_ = any_rough(walls); }
  bool controlled() const { return controlled_; }
  bool rough() const { return rough_; }
  // Step 2 of a run: the controlled walls steer from their loads (steer), every wall moves by one step, and the
  // discs glued to a rough wall move with it. Returns the largest distance a glued disc moved (0 without rough
  // walls): it moves after the discs' displacement was measured, so the caller adds it to that bound.
  double move_walls(WallSet& walls, DiscStore& discs, const Domain& domain, double thickness, double dt) const;
  // The walls' work on the free discs through the glued ones (rough walls), the trapezoid of the last and this
  // step's reaction forces: glued_work_before() takes the last step's half before this step's sums start;
  // add_glued_work() after the sums adds it and this step's half to W_w (nothing without rough walls).
  void glued_work_before(const DiscStore& discs, double dt) { last_half_ = rough_ ? glued_work_half(discs, dt) : 0.0; }
  void add_glued_work(const DiscStore& discs, double dt, double& W_w) const {
    if (!rough_) return;
    W_w += last_half_;
    W_w += glued_work_half(discs, dt);
  }
  // A wall's load: its own contacts plus, for a rough wall, the contacts of free discs with the discs glued
  // to it (the pair rows with exactly one glued disc), each counted once over the ranks (booked rows).
  void measure(WallSet& walls, const DiscStore& discs, const Domain& domain, const ContactTable& pairs,
               const ContactTable& wall_rows, const Communicator& comm) const;
  // The same in two halves, so that the sums ride in the step's fused reduction: local_loads() then, after
  // the reduction, apply() with the slots that add_to() returned.
  static WallLoads local_loads(const WallSet& walls, const DiscStore& discs, const Domain& domain,
                               const ContactTable& pairs, const ContactTable& wall_rows);
  static void apply(WallSet& walls, const FusedReduction& r, const std::vector<std::array<std::size_t, 4>>& slots);
  void steer(WallSet& walls, const Domain& domain, double thickness, double dt) const;
  static BoxGeometry box(const WallSet& walls, const Domain& domain);

  // Rough walls (walls.rough). glue(): at the start of a stage, each owned disc whose centre lies within
  // `depth` of a rough wall (the first one) is glued to it: it moves with that wall, does not rotate and is
  // integrated no more. move_glued(): the glued discs' step with their walls' velocities.
  // glued_work_half(): half of the trapezoid of the walls' work on the free discs through the glued ones,
  // -F.v dt / 2 summed over the owned glued discs (F: the free discs' force on them, their contact sum).
  // glued_counts(): owned discs glued to each wall; one entry more counts those glued to a wall index
  // beyond `n_walls` (a damaged file).
  static void glue(DiscStore& discs, const WallSet& walls, double depth);
  static void move_glued(DiscStore& discs, const WallSet& walls, const Domain& domain, double dt);
  static double glued_work_half(const DiscStore& discs, double dt);
  static std::vector<std::int64_t> glued_counts(const DiscStore& discs, std::size_t n_walls);
  // Normal stress on a box wall [Pa]: its normal force over (length x thickness); 0 when not a box wall.
  static double stress(const Wall& w, const BoxGeometry& g, double thickness);

 private:
  double gain_, v_max_, k_n_, c_n_;
  bool controlled_ = false, rough_ = false;
  double last_half_ = 0.0;
};

}  // namespace rondel
