#include "app/PhaseTimes.hpp"

#include <cstdio>

namespace rondel {

std::string PhaseTimes::line_since(const PhaseTimes& start) const {
  std::array<double, count> d{};
  double sum = 0.0;
  for (int p = 0; p < count; ++p) sum += d[p] = seconds_[p] - start.seconds_[p];
  std::string line = "phases:";
  char buf[64];
  for (int p = 0; p < count; ++p) {
    std::snprintf(buf, sizeof buf, "%s %s %.0f %%", p ? "," : "", name(static_cast<Phase>(p)),
                  sum > 0.0 ? 100.0 * d[p] / sum : 0.0);
    line += buf;
  }
  return line;
}

}  // namespace rondel
