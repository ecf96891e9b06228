#pragma once
// Test support: swallows std::cout while alive (Simulation::run logs there on rank 0).
#include <iostream>
#include <sstream>
#include <string>

namespace rondel::test {

class QuietCout {
 public:
  QuietCout() : old_(std::cout.rdbuf(sink_.rdbuf())) {}
  ~QuietCout() { std::cout.rdbuf(old_); }
  QuietCout(const QuietCout&) = delete;
  QuietCout& operator=(const QuietCout&) = delete;
  // What was written while swallowed.
  std::string text() const { return sink_.str(); }

 private:
  std::ostringstream sink_;
  std::streambuf* old_;
};

}  // namespace rondel::test
