#pragma once
// The terms of the energy ledger (docs/physics.md section 5), declared once. The per-step accumulation
// (LedgerStep, EnergyLedger::add), the sums over ranks, the columns of diagnostics.csv and the /ledger
// attributes of a checkpoint (written and read back) all loop over LedgerTerms::visit_terms, so a new term
// is one member and one line there. It lives in core so that the diagnostics writer (core) and the ledger
// (physics) share it.
#include <string_view>

namespace rondel {

// What each ledger term is.
enum LedgerTermUse : unsigned {
  kTermRankShare = 1u,    // each rank integrates the share it books; the run's value is the sum over ranks
  kTermKernel = 2u,       // booked by the contact kernel (LedgerStep) and added to the ledger every step
  kTermWork = 4u,         // a work: a diagnostics.csv column, before E_stored
  kTermDissipation = 8u,  // a dissipation by mechanism: a diagnostics.csv column, after E_stored
  kTermOfMotion = 16u,    // taken from the discs' motion by the integrator, not through the contacts: not a part
                          // of -W_c (D_other leaves it out), it enters the ledger's balance itself
  kTermCount = 32u,       // a count of events (the bonds' breaks by mode), not an energy: a diagnostics.csv column
                          // at the end; kept in the ledger so that it sums over ranks and is checkpointed alike
};

struct LedgerTermInfo {
  std::string_view name;    // the attribute under a checkpoint's /ledger
  std::string_view column;  // the diagnostics.csv column ("" when the term has none)
  unsigned uses = 0;
};

// The ledger's values [J per thickness]. Works: of gravity W_g, of moving walls on discs W_w, of the contact
// forces and couples W_n + W_t + W_r on the relative motion (negative when they resist). Dissipation by
// mechanism (>= 0): Coulomb slip, rolling plastic work, rolling dashpots, the stored rolling energy released
// when brittle contacts break and the normal law's hysteresis (walton_braun); and the work taken by the integrator's
// local damping (run.local_damping; 0 when it is off).
struct LedgerTerms {
  double KE0 = 0.0;  // kinetic energy at the start
  double W_g = 0.0, W_w = 0.0, W_n = 0.0, W_t = 0.0, W_r = 0.0;
  double W_b = 0.0;       // of the parallel bonds on the relative motion (docs/physics.md section 12; else 0)
  double W_cell = 0.0;    // of a deforming periodic cell on the discs (docs/physics.md section 10; 0 in a standing box)
  double W_driver = 0.0;  // of a script on the discs: the kinetic energy its writes changed (docs/python.md; else 0)
  double D_slip = 0.0, D_r_plastic = 0.0, D_r_dashpot = 0.0, E_r_break = 0.0;
  double D_n_hyst = 0.0;   // the hysteresis of a normal law whose unloading is stiffer (walton_braun; else 0)
  double E_b_break = 0.0;  // what the parallel bonds held when they broke (else 0)
  double n_b_tension = 0.0, n_b_shear = 0.0;  // the bonds broken so far, by mode (counts, exact below 2^53)
  double D_damping = 0.0;
  double scale = 0.0;  // largest of KE, |W_g|, |W_w| seen at the diagnostics so far

  // Visits every term in the checkpoint's order with its description and that term of each of `terms`
  // (LedgerTerms or types derived from it): visit(info, term_of_terms...). Always inlined: the contact
  // kernel merges its step through it, and a call left there changes how the compiler inlines the kernel.
  template <class Visitor, class... Terms>
  [[gnu::always_inline]] static void visit_terms(Visitor&& visit, Terms&... terms) {
    constexpr unsigned kWorkShare = kTermWork | kTermRankShare;
    constexpr unsigned kKernelWork = kWorkShare | kTermKernel;
    constexpr unsigned kKernelLoss = kTermDissipation | kTermRankShare | kTermKernel;
    visit(LedgerTermInfo{"KE0", "", 0u}, terms.KE0...);
    visit(LedgerTermInfo{"W_g", "W_gravity", kWorkShare}, terms.W_g...);
    visit(LedgerTermInfo{"W_w", "W_walls", kKernelWork}, terms.W_w...);
    visit(LedgerTermInfo{"W_n", "W_normal", kKernelWork}, terms.W_n...);
    visit(LedgerTermInfo{"W_t", "W_tangential", kKernelWork}, terms.W_t...);
    visit(LedgerTermInfo{"W_r", "W_rolling", kKernelWork}, terms.W_r...);
    visit(LedgerTermInfo{"W_b", "W_bonds", kKernelWork}, terms.W_b...);
    visit(LedgerTermInfo{"W_cell", "W_cell", kKernelWork}, terms.W_cell...);
    visit(LedgerTermInfo{"W_driver", "W_driver", kWorkShare}, terms.W_driver...);
    visit(LedgerTermInfo{"D_slip", "D_slip", kKernelLoss}, terms.D_slip...);
    visit(LedgerTermInfo{"D_r_plastic", "D_rolling_plastic", kKernelLoss}, terms.D_r_plastic...);
    visit(LedgerTermInfo{"D_r_dashpot", "D_rolling_dashpot", kKernelLoss}, terms.D_r_dashpot...);
    visit(LedgerTermInfo{"E_r_break", "E_rolling_break", kKernelLoss}, terms.E_r_break...);
    visit(LedgerTermInfo{"D_n_hyst", "D_normal_hysteresis", kKernelLoss}, terms.D_n_hyst...);
    visit(LedgerTermInfo{"E_b_break", "E_bond_break", kKernelLoss}, terms.E_b_break...);
    visit(LedgerTermInfo{"D_damping", "D_damping", kTermDissipation | kTermRankShare | kTermOfMotion},
          terms.D_damping...);
    visit(LedgerTermInfo{"scale", "", 0u}, terms.scale...);
    constexpr unsigned kKernelCount = kTermCount | kTermRankShare | kTermKernel;
    visit(LedgerTermInfo{"n_b_tension", "bond_breaks_tension", kKernelCount}, terms.n_b_tension...);
    visit(LedgerTermInfo{"n_b_shear", "bond_breaks_shear", kKernelCount}, terms.n_b_shear...);
  }
  // Adds the terms of `other` that have `use` (this step's terms to a total).
  [[gnu::always_inline]] void add_terms(const LedgerTerms& other, unsigned use) {
    visit_terms(
        [use](const LedgerTermInfo& t, double& total, const double& value) {
          if (t.uses & use) total += value;
        },
        *this, other);
  }
  template <class Visitor>
  void for_each_term(Visitor&& visit) {
    visit_terms(visit, *this);
  }
  template <class Visitor>
  void for_each_term(Visitor&& visit) const {
    visit_terms(visit, *this);
  }
};

}  // namespace rondel
