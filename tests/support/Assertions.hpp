#pragma once
// Test support: assertions whose failure message says what differs (bits in hex, the first differing
// line of two texts, the missing word of an error message).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "support/Format.hpp"

namespace rondel::test {

// The same 64 bits (so -0.0 differs from 0.0 and NaN equals the same NaN), shown in hex when not.
inline ::testing::AssertionResult same_bits(double a, double b) {
  if (std::memcmp(&a, &b, sizeof a) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << hex(a) << " and " << hex(b) << " differ";
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// "line k: <name_a> '...', <name_b> '...'" for the first line where two texts differ ("" when equal).
inline std::string first_difference(const std::string& a, const std::string& b, const std::string& name_a = "expected",
                                    const std::string& name_b = "actual") {
  const auto x = lines_of(a), y = lines_of(b);
  for (std::size_t k = 0; k < std::max(x.size(), y.size()); ++k) {
    const std::string l = k < x.size() ? x[k] : "<none>", r = k < y.size() ? y[k] : "<none>";
    if (l != r) return "line " + std::to_string(k) + ": " + name_a + " '" + l + "', " + name_b + " '" + r + "'";
  }
  return "";
}

// Two texts equal line for line; the failure names the first differing line.
inline ::testing::AssertionResult same_text(const std::string& expected, const std::string& actual) {
  if (expected == actual) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << first_difference(expected, actual);
}

// An error message that names `what`.
inline ::testing::AssertionResult names(const std::string& message, const std::string& what) {
  if (message.find(what) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "the message does not name '" << what << "': '" << message << "'";
}

}  // namespace rondel::test
