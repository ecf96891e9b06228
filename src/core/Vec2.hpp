#pragma once
// A 2D vector of doubles. Plain arithmetic only, so every rank evaluates the same expressions in the
// same order (docs/design.md section 5; compiled with -ffp-contract=off).
namespace rondel {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline Vec2& operator+=(Vec2& a, Vec2 b) {
  a.x += b.x;
  a.y += b.y;
  return a;
}
inline Vec2& operator-=(Vec2& a, Vec2 b) {
  a.x -= b.x;
  a.y -= b.y;
  return a;
}
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z-component of a x b.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// z x a: a turned by +90 degrees.
inline Vec2 perp(Vec2 a) { return {-a.y, a.x}; }

}  // namespace rondel
