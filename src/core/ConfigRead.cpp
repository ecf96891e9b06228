#include "core/ConfigRead.hpp"

#include <algorithm>
#include <boost/any.hpp>
#include <cmath>
#include <cstdint>
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

namespace {

// The value of a number key as a double (integers too: their ranges are doubles).
double number_of(const boost::any& v) {
  if (auto p = boost::any_cast<double>(&v)) return *p;
  if (auto p = boost::any_cast<std::int64_t>(&v)) return static_cast<double>(*p);
  if (auto p = boost::any_cast<int>(&v)) return static_cast<double>(*p);
  if (auto p = boost::any_cast<std::uint64_t>(&v)) return static_cast<double>(*p);
  return NAN;
}

std::string value_text(const boost::any& v) {
  std::ostringstream s;
  s.precision(10);
  if (auto p = boost::any_cast<double>(&v))
    s << *p;
  else if (auto p = boost::any_cast<std::int64_t>(&v))
    s << *p;
  else if (auto p = boost::any_cast<int>(&v))
    s << *p;
  else if (auto p = boost::any_cast<std::uint64_t>(&v))
    s << *p;
  return s.str();
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

}  // namespace

void validate_values(const std::vector<KeySpec>& keys, const boost::program_options::variables_map& vm) {
  auto list = [](const std::vector<std::string>& words) {
    std::string s;
    for (const std::string& w : words) s += (s.empty() ? "" : " | ") + w;
    return s;
  };
  for (const KeySpec& k : keys) {
    if (!vm.count(k.key) || vm[k.key].defaulted()) continue;
    const boost::any& value = vm[k.key].value();
    if (k.type == KeyType::real || k.type == KeyType::integer) {
      check(k.range.contains(number_of(value)), k.key, "must be " + k.range.text(), value_text(value));
    } else if (k.type == KeyType::numbers || k.type == KeyType::records) {
      const std::string text = boost::any_cast<std::string>(value);
      for (const auto& record : records(text, k.key))
        for (double v : record) check(k.range.contains(v), k.key, "every number must be " + k.range.text(), num(v));
    } else if (k.type == KeyType::choice) {
      const std::string word = boost::any_cast<std::string>(value);
      check(std::find(k.allowed.begin(), k.allowed.end(), word) != k.allowed.end(), k.key, list(k.allowed), word);
    } else if (k.type == KeyType::words && !k.allowed.empty()) {
      for (const std::string& word : split_words(boost::any_cast<std::string>(value)))
        check(std::find(k.allowed.begin(), k.allowed.end(), word) != k.allowed.end(), k.key,
              "each word one of " + list(k.allowed), word);
    }
  }
}

void refuse_empty_flags(const std::vector<KeySpec>& keys, const std::vector<std::string>& args,
                        const std::string& ini_text) {
  auto is_flag = [&keys](const std::string& key) {
    for (const KeySpec& k : keys)
      if (k.key == key) return k.type == KeyType::flag;
    return false;
  };
  auto refuse = [](const std::string& key, const std::string& where) {
    throw ConfigError("key '" + key + "' has an empty value" + where + ": give true or false");
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) != 0) continue;
    const auto eq = a.find('=');
    const std::string key = a.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
    if (!is_flag(key)) continue;
    const bool empty = eq != std::string::npos ? trimmed(a.substr(eq + 1)).empty()
                                               : i + 1 < args.size() && trimmed(args[i + 1]).empty();
    if (empty) refuse(key, " on the command line");
  }
  std::istringstream in(ini_text);
  std::string section, line;
  for (std::size_t lineno = 1; std::getline(in, line); ++lineno) {
    line = trimmed(line.substr(0, line.find('#')));
    if (line.empty() || line[0] == ';') continue;
    if (line[0] == '[') {
      section = trimmed(line.substr(1, line.find(']') - 1));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string name = trimmed(line.substr(0, eq));
    const std::string key = section.empty() ? name : section + "." + name;
    if (is_flag(key) && trimmed(line.substr(eq + 1)).empty()) refuse(key, " (line " + std::to_string(lineno) + ")");
  }
}

}  // namespace rondel::config
