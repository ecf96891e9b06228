#include "parallel/Hilbert.hpp"

#include <algorithm>

namespace rondel {

namespace {
// The classic iterative conversions between (x, y) and the distance along the curve on an n x n square
// (n a power of two).
void rotate(std::uint64_t n, std::uint64_t& x, std::uint64_t& y, std::uint64_t rx, std::uint64_t ry) {
  if (ry == 0) {
    if (rx == 1) x = n - 1 - x, y = n - 1 - y;
    std::swap(x, y);
  }
}
std::uint64_t overlap(std::uint64_t lo, std::uint64_t s, std::uint64_t n) {
  return lo >= n ? 0 : std::min(lo + s, n) - lo;
}
}  // namespace

HilbertGrid::HilbertGrid(int nx, int ny) : nx_(nx), ny_(ny) {
  while (side_ < static_cast<std::uint64_t>(std::max(nx, ny))) side_ *= 2;
}

std::uint64_t HilbertGrid::key(int cx, int cy) const {
  std::uint64_t x = static_cast<std::uint64_t>(cx), y = static_cast<std::uint64_t>(cy), d = 0;
  for (std::uint64_t s = side_ / 2; s > 0; s /= 2) {
    const std::uint64_t rx = (x & s) > 0 ? 1 : 0, ry = (y & s) > 0 ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    rotate(side_, x, y, rx, ry);
  }
  return d;
}

void HilbertGrid::point(std::uint64_t key, int& cx, int& cy) const {
  std::uint64_t x = 0, y = 0, t = key;
  for (std::uint64_t s = 1; s < side_; s *= 2) {
    const std::uint64_t rx = 1 & (t / 2), ry = 1 & (t ^ rx);
    rotate(s, x, y, rx, ry);
    x += s * rx;
    y += s * ry;
    t /= 4;
  }
  cx = static_cast<int>(x);
  cy = static_cast<int>(y);
}

std::uint64_t HilbertGrid::node_cells(std::uint64_t b, std::uint64_t s) const {
  // The keys [b, b + s^2) of an aligned node fill the aligned s x s square around point(b).
  int cx = 0, cy = 0;
  point(b, cx, cy);
  const std::uint64_t x0 = static_cast<std::uint64_t>(cx) / s * s, y0 = static_cast<std::uint64_t>(cy) / s * s;
  return overlap(x0, s, static_cast<std::uint64_t>(nx_)) * overlap(y0, s, static_cast<std::uint64_t>(ny_));
}

std::uint64_t HilbertGrid::count_below(std::uint64_t k) const {
  std::uint64_t count = 0, b = 0;
  for (std::uint64_t s = side_; s >= 1; s /= 2) {
    const std::uint64_t size = s * s;
    if (k >= b + size) return count + node_cells(b, s);
    if (k <= b) return count;
    if (s == 1) return count;  // k = b exactly was handled; a single key below k is the node itself
    // Descend: whole children before the one holding k count fully.
    const std::uint64_t child = size / 4, q = (k - b) / child;
    for (std::uint64_t c = 0; c < q; ++c) count += node_cells(b + c * child, s / 2);
    b += q * child;
  }
  return count;
}

std::uint64_t HilbertGrid::key_of_cell_number(std::uint64_t m) const {
  std::uint64_t b = 0;
  for (std::uint64_t s = side_; s > 1; s /= 2) {
    const std::uint64_t child = s * s / 4;
    for (std::uint64_t c = 0; c < 4; ++c) {
      const std::uint64_t n = node_cells(b + c * child, s / 2);
      if (m < n) {
        b += c * child;
        break;
      }
      m -= n;
    }
  }
  return b;
}

void HilbertGrid::for_each_in(std::uint64_t lo, std::uint64_t hi, const std::function<void(int, int)>& f) const {
  for_each_key_in(lo, hi, [&f](std::uint64_t, int cx, int cy) { f(cx, cy); });
}

void HilbertGrid::for_each_key_in(std::uint64_t lo, std::uint64_t hi,
                                  const std::function<void(std::uint64_t, int, int)>& f) const {
  if (lo < hi) visit(0, side_, lo, hi, f);
}

void HilbertGrid::visit(std::uint64_t b, std::uint64_t s, std::uint64_t lo, std::uint64_t hi,
                        const std::function<void(std::uint64_t, int, int)>& f) const {
  if (b + s * s <= lo || b >= hi || node_cells(b, s) == 0) return;
  if (s == 1) {
    int cx = 0, cy = 0;
    point(b, cx, cy);
    f(b, cx, cy);
    return;
  }
  const std::uint64_t child = s * s / 4;
  for (std::uint64_t c = 0; c < 4; ++c) visit(b + c * child, s / 2, lo, hi, f);
}

}  // namespace rondel
