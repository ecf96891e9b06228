#pragma once
// The configuration's keys as rows (docs/design.md section 8): each row declares a key once, with the field it
// fills, its default, its range or the words it allows, its unit and its help. From the row come the key's
// declaration to Boost (the parse and --help), its KeySpec (type, range, words: the validation pass) and its
// reader, which fills the field from the parsed value. Only rules across keys are written by hand.
#include <boost/program_options.hpp>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
#include "core/LawSpec.hpp"

namespace rondel::config {

// A word a choice key allows, the value it stands for, and what it means ("" when the word says it).
template <class V>
struct Choice {
  const char* word;
  V value;
  const char* help = "";
};

// "a | b | c", or with meanings "a (meaning) | b | c".
template <class V>
std::string choice_words(std::type_identity_t<std::span<const Choice<V>>> choices, bool with_help) {
  std::string s;
  for (const Choice<V>& c : choices) {
    s += (s.empty() ? "" : " | ") + std::string(c.word);
    if (with_help && *c.help) s += std::string(" (") + c.help + ")";
  }
  return s;
}

// Where a row's value goes in the target T: one of its members (at(&Config::steps)), or a member of one of its
// members (at(&Config::scene, &SceneConfig::nx)).
template <class T, class M>
struct Field {
  std::function<M&(T&)> of;
};
template <class T, class M>
Field<T, M> at(M T::*member) {
  return {[member](T& t) -> M& { return t.*member; }};
}
template <class T, class P, class M>
Field<T, M> at(P T::*part, M P::*member) {
  return {[part, member](T& t) -> M& { return (t.*part).*member; }};
}
template <class T, class P, class Q, class M>
Field<T, M> at(P T::*part, Q P::*sub, M Q::*member) {
  return {[part, sub, member](T& t) -> M& { return ((t.*part).*sub).*member; }};
}

// A row's reader: fills its field from the parsed values (Boost puts the defaults in them too).
template <class T>
using KeyReader = std::function<void(const boost::program_options::variables_map&, T&)>;

// The rows of one part of the schema ([run], [material.NAME], ...), filling a T.
template <class T>
class KeyTable {
 public:
  KeyTable(boost::program_options::options_description& options, std::vector<KeySpec>& keys,
           std::vector<KeyReader<T>>* readers = nullptr)
      : options_(options), keys_(keys), readers_(readers) {}

  // A number (a double or an integer type) with a default.
  template <class M>
  KeyTable& number(const std::string& key, Field<T, M> field, M def, const char* unit, const Range& range,
                   const std::string& help) {
    declare_number<M>(key, def, unit, range, help);
    read<M>(key, field);
    return *this;
  }
  // A number without a default: required (`why`: the reason the message gives), else left as it is unless given.
  template <class M>
  KeyTable& number_without_default(const std::string& key, Field<T, M> field, const char* unit, const Range& range,
                                   const std::string& help, bool required, const std::string& why = "") {
    declare_number<M>(key, std::nullopt, unit, range, help + (required ? " (required)" : ""));
    if (readers_)
      readers_->push_back([key, field, required, why](const boost::program_options::variables_map& vm, T& t) {
        if (vm.count(key))
          field.of(t) = vm[key].as<M>();
        else if (required)
          throw ConfigError("missing required key '" + key + "'" + why);
      });
    return *this;
  }
  // A number that a rule reads by hand (a law parameter fills its ContactParams field through its ParamSpec).
  template <class M>
  KeyTable& declare_number(const std::string& key, std::optional<M> def, const char* unit, const Range& range,
                           const std::string& help) {
    static_assert(std::is_arithmetic_v<M> && !std::is_same_v<M, bool>);
    spec(key, std::is_floating_point_v<M> ? KeyType::real : KeyType::integer, range);
    declare(key, def ? with_default(*def) : boost::program_options::value<M>(), unit, help, range);
    return *this;
  }
  KeyTable& flag(const std::string& key, Field<T, bool> field, bool def, const std::string& help);
  // A flag that a rule reads by hand (def: its default, or none).
  KeyTable& declare_flag(const std::string& key, std::optional<bool> def, const std::string& help);
  KeyTable& text(const std::string& key, Field<T, std::string> field, const char* def, const char* unit,
                 const std::string& help);
  // One of `choices`, read into the field as its value; the help lists the words (with their meanings). An
  // empty `def` makes the key required.
  template <class V>
  KeyTable& choice(const std::string& key, Field<T, V> field, const std::string& def,
                   std::type_identity_t<std::span<const Choice<V>>> choices, const std::string& help) {
    std::vector<std::string> words;
    for (const Choice<V>& c : choices) words.emplace_back(c.word);
    keys_.push_back({key, KeyType::choice, kAnyNumber, words});
    auto* value = boost::program_options::value<std::string>();
    if (!def.empty()) value->default_value(def);
    declare(key, value, "-", help + (def.empty() ? " (required)" : "") + ": " + choice_words<V>(choices, true),
            kAnyNumber);
    if (readers_)
      readers_->push_back([key, field, list = std::vector<Choice<V>>(choices.begin(), choices.end())](
                              const boost::program_options::variables_map& vm, T& t) {
        const std::span<const Choice<V>> all(list);
        if (!vm.count(key))
          throw ConfigError("missing required key '" + key + "' (" + choice_words<V>(all, false) + ")");
        const std::string word = vm[key].as<std::string>();
        for (const Choice<V>& c : list)
          if (word == c.word) return void(field.of(t) = c.value);
        throw ConfigError("key '" + key + "' = " + word + " is not allowed: " + choice_words<V>(all, false));
      });
    return *this;
  }
  // A word of `allowed` that a rule reads by hand (a word-valued law parameter); `def`: its default, or none.
  KeyTable& declare_choice(const std::string& key, std::optional<std::string> def,
                           const std::vector<std::string>& allowed, const std::string& help);
  // Whitespace-separated words, each one of `allowed` (any word when empty).
  KeyTable& words(const std::string& key, Field<T, std::vector<std::string>> field, const char* def, const char* unit,
                  const std::string& help, const std::vector<std::string>& allowed = {});
  // Whitespace-separated numbers, each in `each`; default none.
  KeyTable& numbers(const std::string& key, Field<T, std::vector<double>> field, const char* unit, const Range& each,
                    const std::string& help);
  // ';'-separated records of whitespace-separated numbers, each in `each`; default none.
  KeyTable& records(const std::string& key, Field<T, std::vector<std::vector<double>>> field, const char* unit,
                    const Range& each, const std::string& help);

 private:
  static constexpr Range kAnyNumber{-INFINITY, INFINITY, false, false};
  template <class M>
  static boost::program_options::typed_value<M>* with_default(M def) {
    return boost::program_options::value<M>()->default_value(def);
  }
  // Doubles print their shortest form in --help ("0.2", not "0.20000000000000001").
  static boost::program_options::typed_value<double>* with_default(double def);
  template <class M>
  void read(const std::string& key, Field<T, M> field) {
    if (readers_)
      readers_->push_back(
          [key, field](const boost::program_options::variables_map& vm, T& t) { field.of(t) = vm[key].as<M>(); });
  }
  void spec(const std::string& key, KeyType type, const Range& range) { keys_.push_back({key, type, range, {}}); }
  // The Boost declaration: "[unit] help, RANGE" (no range for any finite number).
  void declare(const std::string& key, const boost::program_options::value_semantic* value, const char* unit,
               const std::string& help, const Range& range, const char* each = "");

  boost::program_options::options_description& options_;
  std::vector<KeySpec>& keys_;
  std::vector<KeyReader<T>>* readers_;
};

// Whitespace-separated numbers; ';'-separated records of them. Errors name `key`.
std::vector<double> numbers(const std::string& text, const std::string& key);
std::vector<std::vector<double>> records(const std::string& text, const std::string& key);
std::vector<std::string> split_words(const std::string& text);

}  // namespace rondel::config
