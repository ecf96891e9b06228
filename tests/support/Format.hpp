#pragma once
// Test support: numbers written for INI and CSV text, so that a test's scene reads back the same bits.
#include <cstdio>
#include <string>

namespace rondel::test {

// Shortest round-trip form is not needed: 17 significant digits read back as the same double.
inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Hexadecimal float (C99 %a): every bit visible, for messages and bit-exact texts.
inline std::string hex(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

}  // namespace rondel::test
