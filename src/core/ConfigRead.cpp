#include "core/ConfigRead.hpp"

#include <cmath>
#include <sstream>

namespace rondel::config {

void check(bool ok, const std::string& key, const std::string& allowed, const std::string& got) {
  if (!ok) throw ConfigError("key '" + key + "' = " + got + " is not allowed: " + allowed);
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

void positive(const Reader& r, const std::string& key) {
  const double v = r.get<double>(key);
  check(v > 0.0 && std::isfinite(v), key, "must be > 0", num(v));
}

void non_negative(double v, const std::string& key) {
  check(v >= 0.0 && std::isfinite(v), key, "must be >= 0", num(v));
}

void in_range(double v, const Range& range, const std::string& key) {
  check(range.contains(v), key, "must be " + range.text(), num(v));
}

std::vector<double> numbers(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::vector<double> out;
  std::string tok;
  while (in >> tok) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(tok, &used));
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::exception&) {
      throw ConfigError("key '" + key + "': '" + tok + "' is not a number");
    }
  }
  return out;
}

std::vector<std::vector<double>> records(const std::string& text, const std::string& key) {
  std::vector<std::vector<double>> out;
  std::istringstream in(text);
  std::string rec;
  while (std::getline(in, rec, ';')) {
    auto v = numbers(rec, key);
    if (!v.empty()) out.push_back(std::move(v));
  }
  return out;
}

}  // namespace rondel::config
