#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Wall.hpp"

namespace rondel {

// Cell grid plus Verlet list with a skin. A pair is a candidate when its gap is below the skin; the list
// is rebuilt when the largest disc displacement since the last build passes half the skin (or a disc and a
// wall together close more than the skin). Cells have side >= 2 R_max + skin, so polydisperse radii are
// found by the 3 x 3 stencil; discs outside a non-periodic box are clamped into the edge cells.
class NeighbourList {
 public:
  explicit NeighbourList(double skin) : skin_(skin) {}

  double skin() const { return skin_; }
  // A deforming cell's motion bound: the time step and the interaction range of the largest disc of the run (the
  // same on every rank).
  void set_cell_bound(double dt, double range) { dt_ = dt, cell_range_ = range; }
  // Interaction range for a largest radius: the cell side must be at least this.
  double range(double R_max) const { return 2.0 * R_max + skin_; }

  // Fills `pairs` and `wall_rows` from the discs (owned and ghosts), in ascending key order. The rows they
  // hold on entry are the history source: each new row takes the history of the old row of its key, and
  // the old rows are dropped (no copy of the tables is made). Rows whose two discs are both ghosts are
  // left out.
  void build(const DiscStore& discs, const Domain& domain, WallSet& walls, const ContactParamTable& params,
             ContactTable& pairs, ContactTable& wall_rows);

  // Largest displacement of an owned disc since the last build (minimum image); infinite before a build. In a
  // deforming cell, apart from the mean flow's affine motion (docs/physics.md section 10), and displacement()
  // adds the strain's share (strain_term) to it.
  double max_displacement(const DiscStore& discs, const Domain& domain) const;
  // The step's displacement check without a pass over the discs: an upper bound of max_displacement, kept
  // by adding each drift's largest step `max_step` of a free disc (a disc's displacement is at most the sum
  // of its steps), and replaced by the exact max_displacement whenever it passes half the skin, so that a
  // rebuild is decided on the exact value. Discs glued to a rough wall move with it: their displacement is
  // their wall's since the build.
  double displacement(double max_step, const DiscStore& discs, const Domain& domain, const WallSet& walls);
  // True when the local discs and walls have moved enough to need a new list.
  bool needs_rebuild(double max_disc_disp, const WallSet& walls) const;

  std::size_t builds() const { return builds_; }
  // Bytes this list holds (bins and the positions at the last build; the rows are the ContactTables').
  std::size_t memory_bytes() const {
    return (columns_.capacity() + rows_.capacity() + column_slot_.capacity() + row_slot_.capacity()) * sizeof(int) +
           (cell_start_.capacity() + cell_items_.capacity()) * sizeof(std::uint32_t) +
           position_at_build_.capacity() * sizeof(Vec2);
  }

 private:
  // Bins the local discs (owned and ghosts) into the cells they occupy. The bins cover only the columns and
  // rows that hold a local disc (a compressed grid of the occupied columns x occupied rows), never the whole
  // domain's cell grid, so the memory and the work stay those of this rank's discs (docs/design.md section 6).
  void bin(const DiscStore& discs, const Domain& domain, double R_max);
  // The compressed bin of global column cx and row cy, or -1 when no local disc is in that column or row.
  long bin_of(int cx, int cy) const;
  // The pairs within the interaction range (key, local indices), in ascending key, each once from its lower gid,
  // at least one owned disc, no rigid body with itself; `expected`: about how many (the rows held now).
  std::vector<RowCandidate> candidates(const DiscStore& discs, const Domain& domain, std::size_t expected) const;
  template <class Image>
  std::vector<RowCandidate> candidates_by(const DiscStore& discs, const Image& image, std::size_t expected) const;
  // A deforming cell's strain since the build, G = F - I with F = h h0^-1 (upper triangular), and half its
  // Frobenius norm times the interaction range: a pair whose discs moved with the mean flow comes closer by at
  // most |G| (2 R_max + skin), across the boundary too (F maps the lattice of the build onto today's).
  using Strain = CellGradient;  // the same upper-triangular form as the velocity gradient
  Strain strain(const Domain& domain) const;
  double strain_term(const Domain& domain) const;
  // The wall rows anew (every owned disc within the range of a wall), history kept by key.
  void build_wall_rows(const DiscStore& discs, const WallSet& walls, const ContactParamTable& params,
                       ContactTable& wall_rows) const;

  double skin_;
  CellGrid grid_;
  std::vector<int> columns_, rows_;          // the occupied columns and rows, ascending
  std::vector<int> column_slot_, row_slot_;  // their places by column and row over their span (or empty)
  // Bin b is column b % columns_.size(), row b / it; its discs are cell_items_[cell_start_[b], cell_start_[b + 1]).
  std::vector<std::uint32_t> cell_start_, cell_items_;
  std::vector<Vec2> position_at_build_;
  Domain cell_at_build_;
  double dt_ = 0.0, cell_range_ = 0.0;  // set_cell_bound
  double bound_ = INFINITY;             // the bound of displacement() (infinite before a build)
  std::size_t builds_ = 0;
};

}  // namespace rondel
