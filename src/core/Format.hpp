#pragma once
#include <sstream>
#include <string>

namespace rondel {

// A number in a message or a log line: `precision` significant digits, as an ostream prints it.
inline std::string fmt(double v, int precision = 6) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

}  // namespace rondel
