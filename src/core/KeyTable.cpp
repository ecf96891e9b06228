#include "core/KeyTable.hpp"

#include <cmath>
#include <sstream>

#include "core/Config.hpp"
#include "core/Material.hpp"

namespace rondel::config {

namespace po = boost::program_options;

template <class T>
po::typed_value<double>* KeyTable<T>::with_default(double def) {
  std::ostringstream text;
  text << def;
  return po::value<double>()->default_value(def, text.str());
}

template <class T>
void KeyTable<T>::declare(const std::string& key, const po::value_semantic* value, const char* unit,
                          const std::string& help, const Range& range, const char* each) {
  std::string line = "[";
  line.append(unit).append("] ").append(help);
  if (std::isfinite(range.lo) || std::isfinite(range.hi)) line.append(", ").append(each).append(range.text());
  options_.add_options()(key.c_str(), value, line.c_str());
}

template <class T>
KeyTable<T>& KeyTable<T>::flag(const std::string& key, Field<T, bool> field, bool def, const std::string& help) {
  spec(key, KeyType::flag, kAnyNumber);
  declare(key, po::value<bool>()->default_value(def), "-", help + " (true | false)", kAnyNumber);
  read<bool>(key, field);
  return *this;
}

template <class T>
KeyTable<T>& KeyTable<T>::declare_flag(const std::string& key, std::optional<bool> def, const std::string& help) {
  spec(key, KeyType::flag, kAnyNumber);
  auto* value = po::value<bool>();
  if (def) value->default_value(*def);
  declare(key, value, "-", help + " (true | false)", kAnyNumber);
  return *this;
}

template <class T>
KeyTable<T>& KeyTable<T>::text(const std::string& key, Field<T, std::string> field, const char* def, const char* unit,
                               const std::string& help) {
  spec(key, KeyType::text, kAnyNumber);
  declare(key, po::value<std::string>()->default_value(def), unit, help, kAnyNumber);
  read<std::string>(key, field);
  return *this;
}

template <class T>
KeyTable<T>& KeyTable<T>::declare_choice(const std::string& key, std::optional<std::string> def,
                                         const std::vector<std::string>& allowed, const std::string& help) {
  keys_.push_back({key, KeyType::choice, kAnyNumber, allowed});
  std::string any;
  for (const std::string& w : allowed) any += (any.empty() ? "" : " | ") + w;
  auto* value = po::value<std::string>();
  if (def) value->default_value(*def);
  declare(key, value, "-", help + ": " + any, kAnyNumber);
  return *this;
}

template <class T>
KeyTable<T>& KeyTable<T>::words(const std::string& key, Field<T, std::vector<std::string>> field, const char* def,
                                const char* unit, const std::string& help, const std::vector<std::string>& allowed) {
  keys_.push_back({key, KeyType::words, kAnyNumber, allowed});
  std::string any;
  for (const std::string& w : allowed) any += " " + w;
  declare(key, po::value<std::string>()->default_value(def), unit, help + (any.empty() ? "" : ": any of" + any),
          kAnyNumber);
  if (readers_)
    readers_->push_back(
        [key, field](const po::variables_map& vm, T& t) { field.of(t) = split_words(vm[key].as<std::string>()); });
  return *this;
}

template <class T>
KeyTable<T>& KeyTable<T>::numbers(const std::string& key, Field<T, std::vector<double>> field, const char* unit,
                                  const Range& each, const std::string& help) {
  keys_.push_back({key, KeyType::numbers, each, {}});
  declare(key, po::value<std::string>()->default_value(""), unit, help, each, "each number ");
  if (readers_)
    readers_->push_back([key, field](const po::variables_map& vm, T& t) {
      field.of(t) = config::numbers(vm[key].as<std::string>(), key);
    });
  return *this;
}

template <class T>
KeyTable<T>& KeyTable<T>::records(const std::string& key, Field<T, std::vector<std::vector<double>>> field,
                                  const char* unit, const Range& each, const std::string& help) {
  keys_.push_back({key, KeyType::records, each, {}});
  declare(key, po::value<std::string>()->default_value(""), unit, help, each, "each number ");
  if (readers_)
    readers_->push_back([key, field](const po::variables_map& vm, T& t) {
      field.of(t) = config::records(vm[key].as<std::string>(), key);
    });
  return *this;
}

template class KeyTable<Config>;
template class KeyTable<Material>;

std::vector<double> numbers(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::vector<double> out;
  std::string tok;
  while (in >> tok) {
    double v = 0.0;
    try {
      std::size_t used = 0;
      v = std::stod(tok, &used);
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::out_of_range&) {
      throw ConfigError("key '" + key + "': '" + tok + "' is out of the range of a double (about 1e-308 to 1e308)");
    } catch (const std::exception&) {
      throw ConfigError("key '" + key + "': '" + tok + "' is not a number");
    }
    if (!std::isfinite(v))
      throw ConfigError("key '" + key + "': '" + tok + "' is not allowed: every number must be finite");
    out.push_back(v);
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

std::vector<std::string> split_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

}  // namespace rondel::config
