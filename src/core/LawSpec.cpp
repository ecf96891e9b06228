#include "core/LawSpec.hpp"

#include <algorithm>
#include <sstream>

#include "core/Format.hpp"

namespace rondel {

std::string Range::text() const {
  std::ostringstream s;
  if (std::isinf(lo) && std::isinf(hi))
    s << "finite";
  else if (std::isinf(lo))
    s << (hi_open ? "< " : "<= ") << hi;
  else if (std::isinf(hi))
    s << (lo_open ? "> " : ">= ") << lo;
  else
    s << "in " << (lo_open ? "(" : "[") << lo << ", " << hi << (hi_open ? ")" : "]");
  return s.str();
}

std::string ParamSpec::text(double value) const {
  if (!words.empty() && value >= 0.0 && value < static_cast<double>(words.size()))
    return words[static_cast<std::size_t>(value)];
  return fmt(value, 17);
}

int ParamSpec::word_index(const std::string& word) const {
  for (std::size_t k = 0; k < words.size(); ++k)
    if (word == words[k]) return static_cast<int>(k);
  return -1;
}

const ParamSpec* LawBlock::find(const std::string& key) const {
  for (const ParamSpec& p : params)
    if (key == p.key) return &p;
  return nullptr;
}

ContactParams LawBlock::with_examples(ContactParams p) const {
  for (const ParamSpec& spec : params) {
    if (!std::isnan(spec.example))
      p.*spec.target = spec.example;
    else if (spec.presence != Presence::required)
      p.*spec.target = spec.def;
  }
  return p;
}

std::vector<std::string> LawBlock::example_options() const {
  std::vector<std::string> out;
  for (const ParamSpec& spec : params) {
    if (std::isnan(spec.example)) continue;
    out.push_back("--" + std::string(section) + "." + spec.key + "=" + spec.text(spec.example));
  }
  return out;
}

bool LawBlock::in_one_of(const std::string& key) const {
  return std::find_if(one_of.begin(), one_of.end(), [&key](const char* k) { return key == k; }) != one_of.end();
}

std::string LawKind::keywords() const {
  std::string s;
  for (const LawInfo& law : laws) s += (s.empty() ? "" : " | ") + std::string(law.keyword);
  return s;
}

const LawInfo* LawKind::find(const std::string& keyword) const {
  for (const LawInfo& law : laws)
    if (keyword == law.keyword) return &law;
  return nullptr;
}

std::vector<const LawBlock*> LawCatalog::blocks() const {
  std::vector<const LawBlock*> out;
  for (const LawKind* kind : kinds())
    for (const LawInfo& law : kind->laws)
      if (law.block && std::find(out.begin(), out.end(), law.block) == out.end()) out.push_back(law.block);
  if (bonds) out.push_back(bonds);
  return out;
}

}  // namespace rondel
