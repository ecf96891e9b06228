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

HilbertGrid::Node HilbertGrid::child(const Node& n, int q) {
  // The curve of side s is four curves of side h = s / 2, in the quadrants (0, 0), (0, 1), (1, 1), (1, 0) (in
  // units of h), the first transposed and the last reflected about the other diagonal (point()'s rotate, read
  // from the top): a cell p of the child is the node's cell offset + T(p).
  const std::int64_t h = static_cast<std::int64_t>(n.s / 2);
  static constexpr int kRx[4] = {0, 0, 1, 1}, kRy[4] = {0, 1, 1, 0};
  // T(p) = (t0 + ta x + tb y, t1 + tc x + td y) in the node's own coordinates.
  std::int64_t t0 = kRx[q] * h, t1 = kRy[q] * h;
  int ta = 1, tb = 0, tc = 0, td = 1;
  if (q == 0) ta = 0, tb = 1, tc = 1, td = 0;                              // (y, x)
  if (q == 3) ta = 0, tb = -1, tc = -1, td = 0, t0 += h - 1, t1 += h - 1;  // (h - 1 - y, h - 1 - x)
  Node out;
  out.b = n.b + static_cast<std::uint64_t>(q) * static_cast<std::uint64_t>(h * h);
  out.s = static_cast<std::uint64_t>(h);
  out.ox = n.ox + n.a * t0 + n.bx * t1;
  out.oy = n.oy + n.c * t0 + n.d * t1;
  out.a = n.a * ta + n.bx * tc, out.bx = n.a * tb + n.bx * td;
  out.c = n.c * ta + n.d * tc, out.d = n.c * tb + n.d * td;
  return out;
}

void HilbertGrid::square(const Node& n, std::int64_t& x0, std::int64_t& y0, std::int64_t& x1, std::int64_t& y1) {
  const auto s = static_cast<std::int64_t>(n.s) - 1;  // the far corner (s, s) of the node's own square
  const std::int64_t fx = n.ox + (n.a + n.bx) * s, fy = n.oy + (n.c + n.d) * s;
  x0 = std::min(n.ox, fx), x1 = std::max(n.ox, fx) + 1;
  y0 = std::min(n.oy, fy), y1 = std::max(n.oy, fy) + 1;
}

std::uint64_t HilbertGrid::key_at_work(std::uint64_t t, const RectWeight& weight) const {
  Node n = root();
  while (n.s > 1) {
    Node next = n;
    for (int q = 0; q < 4; ++q) {
      next = child(n, q);
      std::int64_t x0, y0, x1, y1;
      square(next, x0, y0, x1, y1);
      x1 = std::min<std::int64_t>(x1, nx_), y1 = std::min<std::int64_t>(y1, ny_);
      const std::uint64_t w = x0 < x1 && y0 < y1 ? weight(static_cast<int>(x0), static_cast<int>(y0),
                                                          static_cast<int>(x1), static_cast<int>(y1))
                                                 : 0;
      if (t < w || q == 3) break;  // (t beyond the last child only by an inconsistent weight: stay in it)
      t -= w;
    }
    n = next;
  }
  return n.b;
}

}  // namespace rondel
