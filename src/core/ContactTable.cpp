#include "core/ContactTable.hpp"

#include <algorithm>

namespace rondel {

ContactTable::ContactTable(std::vector<std::string> slot_names, bool has_moment)
    : slot(slot_names.size()), slot_names_(std::move(slot_names)), has_moment_(has_moment) {}

void ContactTable::clear() {
  key.clear();
  i1.clear();
  i2.clear();
  param.clear();
  for (auto& s : slot) s.clear();
  F_n.clear();
  F_t.clear();
  M1.clear();
  M2.clear();
  f1.clear();
  tq1.clear();
  tq2.clear();
}

void ContactTable::push(ContactKey k, std::int32_t a, std::int32_t b, std::int32_t p) {
  key.push_back(k);
  i1.push_back(a);
  i2.push_back(b);
  param.push_back(p);
  for (auto& s : slot) s.push_back(0.0);
  F_n.push_back(0.0);
  F_t.push_back(0.0);
  if (has_moment_) {
    M1.push_back(0.0);
    M2.push_back(0.0);
  }
  f1.push_back({});
  tq1.push_back(0.0);
  tq2.push_back(0.0);
}

void ContactTable::inherit_history(const ContactTable& old) {
  std::size_t j = 0;
  for (std::size_t r = 0; r < size(); ++r) {
    while (j < old.size() && old.key[j] < key[r]) ++j;
    if (j == old.size()) break;
    if (!(old.key[j] == key[r])) continue;
    for (std::size_t k = 0; k < slot.size(); ++k) slot[k][r] = old.slot[k][j];
    F_n[r] = old.F_n[j];
    F_t[r] = old.F_t[j];
    if (has_moment_) {
      M1[r] = old.M1[j];
      M2[r] = old.M2[j];
    }
    f1[r] = old.f1[j];  // the wall-work trapezoid needs last step's force
  }
}

void ContactTable::push_copy(const ContactTable& src, std::size_t r) {
  push(src.key[r], -1, -1, src.param[r]);
  const std::size_t n = size() - 1;
  for (std::size_t k = 0; k < slot.size(); ++k) slot[k][n] = src.slot[k][r];
  F_n[n] = src.F_n[r];
  F_t[n] = src.F_t[r];
  if (has_moment_) {
    M1[n] = src.M1[r];
    M2[n] = src.M2[r];
  }
  f1[n] = src.f1[r];
  tq1[n] = src.tq1[r];
  tq2[n] = src.tq2[r];
}

void ContactTable::sort_unique_by_key() {
  std::vector<std::size_t> order(size());
  for (std::size_t r = 0; r < order.size(); ++r) order[r] = r;
  std::stable_sort(order.begin(), order.end(), [this](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  ContactTable sorted(slot_names_, has_moment_);
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && key[order[k]] == key[order[k - 1]]) continue;
    sorted.push_copy(*this, order[k]);
    sorted.i1.back() = i1[order[k]];
    sorted.i2.back() = i2[order[k]];
  }
  *this = std::move(sorted);
}

bool ContactTable::has_state(std::size_t r) const {
  if (F_n[r] != 0.0 || F_t[r] != 0.0) return true;
  for (const auto& s : slot)
    if (s[r] != 0.0) return true;
  return has_moment_ && (M1[r] != 0.0 || M2[r] != 0.0);
}

std::size_t ContactTable::memory_bytes() const {
  std::size_t b = key.capacity() * sizeof(ContactKey) + (i1.capacity() + i2.capacity() + param.capacity()) * 4;
  for (const auto& s : slot) b += s.capacity() * sizeof(double);
  b += (F_n.capacity() + F_t.capacity() + M1.capacity() + M2.capacity() + tq1.capacity() + tq2.capacity()) * sizeof(double);
  b += f1.capacity() * sizeof(Vec2);
  return b;
}

}  // namespace rondel
