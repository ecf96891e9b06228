#pragma once
#include <array>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/Domain.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// Loads and motions of the walls (DESIGN.md section 4, step 2).
//  - measure(): each wall's load from the discs in the last step, summed exactly over ranks, so a servo
//    sees the same force on any rank count;
//  - steer(): velocities of controlled walls. A servo moves along its normal with
//      v_n = clamp(gain (F_target - F) / (k_n max(N_c, 1) dt), +-v_max),  F_target = sigma L t,
//    the gain kept below 1 so one step never closes more than the force error (stable for gain < 1);
//    a strain-rate wall moves with v_n = rate x (distance to the opposite box wall).
//  - box geometry: the sample's width and height between the box walls (for stresses and strains).
struct BoxGeometry {
  double width = 0.0, height = 0.0;
  bool has_x = false, has_y = false;  // left and right walls, bottom and top walls
};

class Boundaries {
 public:
  Boundaries(double servo_gain, double servo_max_speed) : gain_(servo_gain), v_max_(servo_max_speed) {}

  bool controlled(const WallSet& walls) const;
  void measure(WallSet& walls, const ContactTable& wall_rows, std::size_t n_owned, const Communicator& comm) const;
  void steer(WallSet& walls, const ContactParamTable& params, const Domain& domain, double thickness, double dt) const;
  static BoxGeometry box(const WallSet& walls, const Domain& domain);
  // Normal stress on a box wall [Pa]: its normal force over (length x thickness); 0 when not a box wall.
  static double stress(const Wall& w, const BoxGeometry& g, double thickness);

 private:
  double gain_, v_max_;
};

}  // namespace rondel
