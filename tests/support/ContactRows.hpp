#pragma once
// Test support: contact-table rows filled and printed column by column through ContactTable's column
// table, so a test covers every column, present and future, without naming them.
#include <cstddef>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/ContactTable.hpp"

namespace rondel::test {

// Sets every column of row r with a use in `only` (the key excepted: it is the row's identity) to
// value(key, c) for the c-th column visited (1, 2, ...); a Vec2 gets (v, -v), an index the value cast.
template <class Value>
void fill_row(ContactTable& t, std::size_t r, Value value, unsigned only = ~0u) {
  int c = 0;
  t.for_each_column([&](std::string_view, unsigned uses, auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    const double v = value(t.key[r], ++c);
    if (!(uses & only)) return;
    if constexpr (std::is_same_v<T, Vec2>) column[r] = Vec2{v, -v};
    if constexpr (std::is_arithmetic_v<T>) column[r] = static_cast<T>(v);
  });
}

// "name=value" of the columns of row r with a use in `only`, in the column table's order (doubles in
// hexadecimal: equal texts are equal bits).
inline std::string row_text(const ContactTable& t, std::size_t r, unsigned only = ~0u) {
  std::ostringstream s;
  s << std::hexfloat;
  t.for_each_column([&](std::string_view name, unsigned uses, const auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    if (!(uses & only)) return;
    s << name << '=';
    if constexpr (std::is_same_v<T, ContactKey>) s << column[r].lo << ':' << column[r].hi;
    if constexpr (std::is_same_v<T, Vec2>) s << column[r].x << ':' << column[r].y;
    if constexpr (std::is_arithmetic_v<T>) s << column[r];
    s << ' ';
  });
  return s.str();
}

}  // namespace rondel::test
