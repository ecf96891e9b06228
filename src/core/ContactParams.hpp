#pragma once
#include <cstddef>
#include <vector>

namespace rondel {

// Contact-law parameters of one material pair (or of a material against the walls). Each law reads only
// its own fields; the config layer fills only the fields of the selected laws. Aligned to 64 bytes, so that an
// entry's size is a power of two (256) and the kernel finds a row's entry with a shift: the size of 200 bytes it
// would have took three instructions per row where 184 took one (callgrind: the wang kernel +1.0 %).
struct alignas(64) ContactParams {
  // linear normal
  double k_n = 0.0;
  double zeta_n = 0.0;      // normal damping ratio, used when c_n_fixed < 0
  double c_n_fixed = -1.0;  // a user-given normal dashpot [N s/m]; < 0 means "from zeta_n"
  double e_n = -1.0;        // a user-given restitution; > 0 means zeta_n is derived from it at set-up
  // hertz / mindlin (docs/physics.md section 6): the restitution e_n above, and the pair constants mixed
  // from the two materials at set-up (E*, G*, beta = ln e/sqrt(ln^2 e + pi^2))
  double E_star = 0.0;
  double G_star = 0.0;
  double beta = 0.0;
  // coulomb tangential
  double k_s = 0.0;
  double zeta_t = 0.0;
  double mu = 0.0;
  // rolling laws (docs/physics.md section 3)
  bool rolling = true;  // false: no rolling resistance at this pair (e.g. frictionless walls)
  double delta = 0.0;   // jiang_*: contact width B = delta r
  double after_break =
      0.0;              // jiang_brittle: 0 reform (the spring restarts after a break), 1 open (M = 0 till it opens)
  double k_r = 0.0;     // wang, alonso_marroquin
  double mu_r = 0.0;    // wang, alonso_marroquin, force_proportional, constant_torque, displacement_damping
  double c_r = 0.0;     // wang, alonso_marroquin rolling dashpot
  double K_r = 0.0;     // iwashita_oda
  double C_r = 0.0;     // iwashita_oda
  double eta = 0.0;     // iwashita_oda
  double f_lim = 0.08;  // constant_torque moment limiter
  double theta_rmax = 0.035;  // displacement_damping
  double nu = 0.0;            // displacement_damping viscous part
  double f_visc = 1.0;        // displacement_damping viscous factor at the limit
  // walton_braun (docs/physics.md section 11): the loading stiffness K1 is k_n; the unloading stiffness K2, given
  // or from the pair's restitution e_wb (K2 = K1/e^2) at set-up
  double k_unload = -1.0;  // < 0: not given
  double e_wb = -1.0;      // < 0: not given
  // parallel bonds ([bonds], docs/physics.md section 12): stiffnesses per area [Pa/m], mean strengths [Pa] with
  // their relative spreads, the section's radius multiplier; kb_n = 0: the pair is not bonded
  double kb_n = 0.0, kb_s = 0.0;
  double sigma_c = 0.0, tau_c = 0.0;
  double sigma_spread = 0.0, tau_spread = 0.0;
  double bond_lambda = 1.0;
};
static_assert(sizeof(ContactParams) == 256, "a parameter entry is 256 bytes: the kernel finds it with a shift");

// Parameters for every (material, material) pair and every (disc material, wall material) pair. A contact
// row holds the index of its entry (pair_index or wall_index, set at the neighbour build), so the kernel's
// lookup is one load whatever the number of materials.
class ContactParamTable {
 public:
  ContactParamTable() = default;
  explicit ContactParamTable(std::size_t n_materials)
      : n_(n_materials), pairs_(n_materials * n_materials), walls_(n_materials * n_materials) {}

  std::size_t n_materials() const { return n_; }
  std::size_t pair_index(std::size_t a, std::size_t b) const { return a * n_ + b; }
  std::size_t wall_index(std::size_t disc, std::size_t wall) const { return disc * n_ + wall; }
  ContactParams& pair(std::size_t a, std::size_t b) { return pairs_[pair_index(a, b)]; }
  const ContactParams& pair(std::size_t a, std::size_t b) const { return pairs_[pair_index(a, b)]; }
  // A disc of material `disc` against a wall of material `wall`.
  ContactParams& wall(std::size_t disc, std::size_t wall = 0) { return walls_[wall_index(disc, wall)]; }
  const ContactParams& wall(std::size_t disc, std::size_t wall = 0) const { return walls_[wall_index(disc, wall)]; }
  std::vector<ContactParams>& pairs() { return pairs_; }
  std::vector<ContactParams>& walls() { return walls_; }
  const std::vector<ContactParams>& pairs() const { return pairs_; }
  const std::vector<ContactParams>& walls() const { return walls_; }

 private:
  std::size_t n_ = 0;
  std::vector<ContactParams> pairs_;
  std::vector<ContactParams> walls_;
};

}  // namespace rondel
