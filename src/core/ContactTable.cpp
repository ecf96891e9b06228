#include "core/ContactTable.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <type_traits>

#include "core/Buffers.hpp"

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

namespace {

constexpr std::uint32_t kNoRow = UINT32_MAX;

// For each of the n ascending keys key_of(0), ..., the row of the same key in `from` (ascending), or kNoRow.
template <class KeyOf>
std::vector<std::uint32_t> match_rows(const std::vector<ContactKey>& from, std::size_t n, KeyOf&& key_of) {
  if (from.size() >= kNoRow) throw std::length_error("a contact table of 2^32 rows or more on one rank");
  std::vector<std::uint32_t> row(n, kNoRow);
  std::size_t j = 0;
  for (std::size_t r = 0; r < n && j < from.size(); ++r) {
    const ContactKey k = key_of(r);
    while (j < from.size() && from[j] < k) ++j;
    if (j < from.size() && from[j] == k) row[r] = static_cast<std::uint32_t>(j);
  }
  return row;
}

}  // namespace

void ContactTable::inherit_history(const ContactTable& old) {
  const std::vector<std::uint32_t> from = match_rows(old.key, size(), [this](std::size_t r) { return key[r]; });
  visit_columns(
      [&from](std::string_view, unsigned uses, auto& column, const auto& source) {
        if (!(uses & kColumnInherit)) return;
        for (std::size_t r = 0; r < from.size(); ++r)
          if (from[r] != kNoRow) column[r] = source[from[r]];
      },
      *this, old);
}

void ContactTable::replace_rows(std::vector<RowCandidate>& found) {
  const std::size_t n = found.size();
  const std::vector<std::uint32_t> from = match_rows(key, n, [&found](std::size_t r) { return found[r].key; });
  for_each_column([](std::string_view, unsigned uses, auto& column) {
    if (!(uses & kColumnInherit)) release(column);  // the keys, indices and parameters are found anew
  });
  key.resize(n), i1.resize(n), i2.resize(n);
  for (std::size_t r = 0; r < n; ++r) key[r] = found[r].key, i1[r] = found[r].i1, i2[r] = found[r].i2;
  release(found);
  param.assign(n, 0);
  for_each_column([&from, n](std::string_view, unsigned uses, auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    if (!(uses & kColumnInherit)) return;
    std::vector<T> next(n, T{});
    for (std::size_t r = 0; r < n; ++r)
      if (from[r] != kNoRow) next[r] = column[from[r]];
    column.swap(next);  // the old column is freed here
  });
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
  bool done = true;  // already in strictly ascending order (a restart's rows on one rank): no copy
  for (std::size_t r = 1; r < size() && done; ++r) done = key[r - 1] < key[r];
  if (done) return;
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
