#include "core/ContactTable.hpp"

#include <algorithm>
#include <type_traits>

namespace rondel {

ContactTable::ContactTable(std::vector<std::string> slot_names, int couples, bool wall_rows)
    : slot(slot_names.size()),
      slot_names_(std::move(slot_names)),
      couples_(static_cast<std::uint8_t>(couples)),
      wall_rows_(wall_rows) {
  for (const auto& s : slot_names_) slot_columns_.push_back("history/" + s);
}

ContactTable ContactTable::bond_table() {
  ContactTable t({"Fb_n", "Fb_s", "Mb"}, 0, false);
  t.bonds_ = true;
  return t;
}

void ContactTable::reserve(std::size_t rows) {
  for_each_column([rows](std::string_view, unsigned, auto& column) { column.reserve(rows); });
}

void ContactTable::clear() {
  for_each_column([](std::string_view, unsigned, auto& column) { column.clear(); });
}

void ContactTable::push(ContactKey k, std::int32_t a, std::int32_t b, std::int32_t p) {
  for_each_column([](std::string_view, unsigned, auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    column.push_back(T{});
  });
  const std::size_t n = size() - 1;
  key[n] = k;
  i1[n] = a;
  i2[n] = b;
  param[n] = p;
}

void ContactTable::inherit_history(const ContactTable& old) {
  std::size_t j = 0;
  for (std::size_t r = 0; r < size(); ++r) {
    while (j < old.size() && old.key[j] < key[r]) ++j;
    if (j == old.size()) break;
    if (!(old.key[j] == key[r])) continue;
    visit_columns(
        [r, j](std::string_view, unsigned uses, auto& column, const auto& from) {
          if (uses & kColumnInherit) column[r] = from[j];
        },
        *this, old);
  }
}

void ContactTable::push_copy(const ContactTable& src, std::size_t r) {
  visit_columns(
      [r](std::string_view, unsigned uses, auto& column, const auto& from) {
        using T = typename std::decay_t<decltype(column)>::value_type;
        column.push_back((uses & kColumnLocalIndex) ? unset_column_value<T>(uses) : from[r]);
      },
      *this, src);
}

void ContactTable::sort_unique_by_key() {
  std::vector<std::size_t> order(size());
  for (std::size_t r = 0; r < order.size(); ++r) order[r] = r;
  std::stable_sort(order.begin(), order.end(), [this](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  ContactTable sorted = empty_like();
  sorted.reserve(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && key[order[k]] == key[order[k - 1]]) continue;
    sorted.push_copy(*this, order[k]);
    sorted.i1.back() = i1[order[k]];
    sorted.i2.back() = i2[order[k]];
  }
  *this = std::move(sorted);
}

bool ContactTable::has_state(std::size_t r) const {
  bool state = bonds_;
  for_each_column([&state, r](std::string_view, unsigned uses, const auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    if constexpr (std::is_same_v<T, double>) state = state || ((uses & kColumnState) && column[r] != 0.0);
  });
  return state;
}

std::size_t ContactTable::memory_bytes() const {
  std::size_t b = 0;
  for_each_column([&b](std::string_view, unsigned, const auto& column) {
    b += column.capacity() * sizeof(typename std::decay_t<decltype(column)>::value_type);
  });
  return b;
}

}  // namespace rondel
