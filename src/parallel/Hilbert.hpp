#pragma once
#include <algorithm>
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
  // f(key, cx, cy) for every in-grid cell with key in [lo, hi), in key order.
  template <class F>
  void for_each_key_in(std::uint64_t lo, std::uint64_t hi, F f) const {
    if (lo < hi) visit(root(), lo, hi, f);
  }
  // The in-grid cells of the rectangle [x0, x1) x [y0, y1) split into nodes of the curve, each taken whole when
  // `whole(b, e)` allows it for its keys [b, e) (a single cell always is): f(b, e, rx0, ry0, rx1, ry1) for each,
  // with the node's cells in the rectangle [rx0, rx1) x [ry0, ry1) (never empty). The nodes visited are those
  // that meet the rectangle and hold a key where `whole` changes its mind: O(log side) per such key, not O(cells).
  template <class Whole, class F>
  void cover(int x0, int y0, int x1, int y1, Whole whole, F f) const {
    if (x0 < x1 && y0 < y1) cover(root(), x0, y0, std::min(x1, nx_), std::min(y1, ny_), whole, f);
  }
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
  template <class F>
  void visit(const Node& n, std::uint64_t lo, std::uint64_t hi, F& f) const {
    if (n.b + n.s * n.s <= lo || n.b >= hi) return;
    if (n.s == 1) {
      if (n.ox < nx_ && n.oy < ny_) f(n.b, static_cast<int>(n.ox), static_cast<int>(n.oy));
      return;
    }
    std::int64_t x0, y0, x1, y1;
    square(n, x0, y0, x1, y1);
    if (x0 >= nx_ || y0 >= ny_) return;  // the node lies beyond the grid
    for (int q = 0; q < 4; ++q) visit(child(n, q), lo, hi, f);
  }
  template <class Whole, class F>
  void cover(const Node& n, int x0, int y0, int x1, int y1, Whole& whole, F& f) const {
    std::int64_t a0, b0, a1, b1;
    square(n, a0, b0, a1, b1);
    a0 = std::max<std::int64_t>(a0, x0), b0 = std::max<std::int64_t>(b0, y0);
    a1 = std::min<std::int64_t>(a1, x1), b1 = std::min<std::int64_t>(b1, y1);
    if (a0 >= a1 || b0 >= b1) return;  // beyond the rectangle (which lies in the grid)
    if (n.s == 1 || whole(n.b, n.b + n.s * n.s)) {
      f(n.b, n.b + n.s * n.s, static_cast<int>(a0), static_cast<int>(b0), static_cast<int>(a1), static_cast<int>(b1));
      return;
    }
    for (int q = 0; q < 4; ++q) cover(child(n, q), x0, y0, x1, y1, whole, f);
  }

  int nx_ = 1, ny_ = 1;
  std::uint64_t side_ = 1;
};

}  // namespace rondel
