#pragma once
// What a pass of the contact kernel (ContactKernel.hpp) takes and gives, apart from the kernel itself: its context
// (the discs, the domain, the walls, the parameter table, the step), the step's ledger terms with its worst overlap,
// and the summary of the contacts' stored energies and states. Code that reads a step's results includes this.
#include <cmath>
#include <cstdint>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/LedgerTerms.hpp"
#include "core/Wall.hpp"

namespace rondel {

// The worst overlap above the context's limit (u_n / smaller radius; 0 when none), and where.
struct WorstOverlap {
  double worst_overlap = 0.0;
  ContactKey worst_key;
  bool worst_at_wall = false;
};

// This step's ledger terms: the kernel books those of kTermKernel (the rest stay zero), and the step's worst
// overlap.
struct LedgerStep : LedgerTerms, WorstOverlap {};

// The contacts now: energy held by their springs [J per thickness], how many carry load, how many slide
// (|F_t| at mu F_n) and how many have yielded in rolling (|M| at the law's cap). Booked rows only.
// The parallel bonds' stored energy and count (booked rows) join them when the scene has bonds.
struct ContactSummary {
  double normal = 0.0, tangential = 0.0, rolling = 0.0;
  std::int64_t contacts = 0, wall_contacts = 0, sliding = 0, rolling_yield = 0;
  double bonds_stored = 0.0;
  std::int64_t bonds = 0;
  double total() const { return normal + tangential + rolling + bonds_stored; }
};

struct KernelContext {
  const DiscStore& discs;
  const Domain& domain;
  const WallSet& walls;
  const ContactParamTable& params;
  double dt;
  double overlap_limit = INFINITY;  // report overlaps above this fraction of the smaller radius
};

}  // namespace rondel
