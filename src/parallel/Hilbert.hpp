#pragma once
#include <cstdint>
#include <functional>

namespace rondel {

// The Hilbert curve over an nx x ny cell grid (docs/scaling.md): the grid lies in the corner of the smallest
// 2^k x 2^k square that holds it, and each cell's key is its index along the square's curve. Keys of cells
// outside the grid are skipped, so the in-grid cells are ordered by key. A contiguous key range is a compact
// region (a curve segment of L cells has a perimeter of order sqrt(L)), which is what the space-filling-curve
// partition cuts into ranks. Every operation below is O(log side) or O(cells visited), never O(all cells).
class HilbertGrid {
 public:
  HilbertGrid() = default;
  HilbertGrid(int nx, int ny);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  // One past the largest key (side^2).
  std::uint64_t key_end() const { return side_ * side_; }
  std::uint64_t cells() const { return static_cast<std::uint64_t>(nx_) * static_cast<std::uint64_t>(ny_); }
  std::uint64_t key(int cx, int cy) const;
  void point(std::uint64_t key, int& cx, int& cy) const;
  // In-grid cells with key < k.
  std::uint64_t count_below(std::uint64_t k) const;
  // The key of the m-th in-grid cell along the curve (m < cells()).
  std::uint64_t key_of_cell_number(std::uint64_t m) const;
  // f(cx, cy) for every in-grid cell with key in [lo, hi), in key order.
  void for_each_in(std::uint64_t lo, std::uint64_t hi, const std::function<void(int, int)>& f) const;
  // The same with each cell's key: f(key, cx, cy).
  void for_each_key_in(std::uint64_t lo, std::uint64_t hi, const std::function<void(std::uint64_t, int, int)>& f) const;

 private:
  // In-grid cells of the aligned node of side s whose first key is b.
  std::uint64_t node_cells(std::uint64_t b, std::uint64_t s) const;
  void visit(std::uint64_t b, std::uint64_t s, std::uint64_t lo, std::uint64_t hi,
             const std::function<void(std::uint64_t, int, int)>& f) const;

  int nx_ = 1, ny_ = 1;
  std::uint64_t side_ = 1;
};

}  // namespace rondel
