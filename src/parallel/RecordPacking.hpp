#pragma once
// Fixed-layout records of discs and contact rows for MPI messages and file blocks. A disc record holds the
// fields whose use matches (DiscStore's field table); a row record holds the record columns of
// ContactTable's column table: the key, the parameter index, the history slots, the last scalars and the
// last force on disc 1.
#include <cstddef>
#include <cstring>
#include <string_view>
#include <type_traits>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/ByteBuffer.hpp"

namespace rondel {

inline void pack_disc(DiscStore& discs, std::size_t i, unsigned use, ByteBuffer& out) {
  discs.for_each_field([&](const char*, unsigned uses, auto& field) {
    if (uses & use) out.put(field[i]);
  });
}

// Appends one disc record; fields the record does not carry get their default value.
inline void append_disc(DiscStore& discs, unsigned use, ByteReader& in) {
  discs.for_each_field([&](const char*, unsigned uses, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    field.push_back((uses & use) ? in.get<T>() : T{});
  });
}

inline void read_disc(DiscStore& discs, std::size_t i, unsigned use, ByteReader& in) {
  discs.for_each_field([&](const char*, unsigned uses, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    if (uses & use) field[i] = in.get<T>();
  });
}

inline std::size_t record_bytes(DiscStore& discs, unsigned use) {
  std::size_t bytes = 0;
  discs.for_each_field([&](const char*, unsigned uses, auto& field) {
    if (uses & use) bytes += sizeof(field[0]);
  });
  return bytes;
}

inline void pack_row(const ContactTable& t, std::size_t r, ByteBuffer& out) {
  t.for_each_column([&](std::string_view, unsigned uses, const auto& column) {
    if (uses & kColumnRecord) out.put(column[r]);
  });
}

// Appends one row record; columns the record does not carry get their unset value (local indices -1).
inline void unpack_row(ContactTable& t, ByteReader& in) {
  t.for_each_column([&](std::string_view, unsigned uses, auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    column.push_back((uses & kColumnRecord) ? in.get<T>() : unset_column_value<T>(uses));
  });
}

// Row r's record (the layout of pack_row) at `out`, for a file block or a routed buffer.
inline void pack_row_bytes(const ContactTable& t, std::size_t r, char* out) {
  t.for_each_column([&](std::string_view, unsigned uses, const auto& column) {
    if (!(uses & kColumnRecord)) return;
    std::memcpy(out, &column[r], sizeof column[0]);
    out += sizeof column[0];
  });
}

// Bytes of one row record of `t`.
inline std::size_t row_bytes(const ContactTable& t) {
  std::size_t bytes = 0;
  t.for_each_column([&](std::string_view, unsigned uses, const auto& column) {
    if (uses & kColumnRecord) bytes += sizeof(column[0]);
  });
  return bytes;
}

}  // namespace rondel
