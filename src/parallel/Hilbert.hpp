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
  // The work of the in-grid cells of a rectangle [x0, x1) x [y0, y1) (within the grid, not empty).
  using RectWeight = std::function<std::uint64_t(int x0, int y0, int x1, int y1)>;
  // The key of the in-grid cell that holds the point t of the work along the curve (cell c holds [before(c),
  // before(c) + w(c)), before(c) the work of the cells of lower key; t below the whole grid's work): a descent of
  // the curve's nodes, O(log side) calls of `weight`.
  std::uint64_t key_at_work(std::uint64_t t, const RectWeight& weight) const;

 private:
  // A node of the curve: its first key b, its side s and the map of its own curve's cells (those of the
  // canonical curve of side s) to the grid's, (x, y) -> (ox + a x + b y, oy + c x + d y).
  struct Node {
    std::uint64_t b, s;
    std::int64_t ox, oy;
    int a, bx, c, d;
  };
  // Its child q (in curve order) and the node's square on the grid, [x0, x1) x [y0, y1).
  static Node child(const Node& n, int q);
  static void square(const Node& n, std::int64_t& x0, std::int64_t& y0, std::int64_t& x1, std::int64_t& y1);
  Node root() const { return {0, side_, 0, 0, 1, 0, 0, 1}; }
  // In-grid cells of the aligned node of side s whose first key is b.
  std::uint64_t node_cells(std::uint64_t b, std::uint64_t s) const;
  void visit(const Node& n, std::uint64_t lo, std::uint64_t hi,
             const std::function<void(std::uint64_t, int, int)>& f) const;

  int nx_ = 1, ny_ = 1;
  std::uint64_t side_ = 1;
};

}  // namespace rondel
