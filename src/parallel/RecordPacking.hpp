#pragma once
// Fixed-layout records of discs and contact rows for MPI messages and file blocks. A disc record holds the
// fields whose use matches (DiscStore's field table); a row record holds the key, the parameter index, the
// history slots, the last scalars and the last force on disc 1.
#include <cstddef>
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
  out.put(t.key[r]);
  out.put(t.param[r]);
  for (const auto& s : t.slot) out.put(s[r]);
  out.put(t.F_n[r]);
  out.put(t.F_t[r]);
  if (t.has_moment()) out.put(t.M1[r]), out.put(t.M2[r]);
  out.put(t.f1[r]);
}

inline void unpack_row(ContactTable& t, ByteReader& in) {
  const auto key = in.get<ContactKey>();
  const auto param = in.get<std::int32_t>();
  t.push(key, -1, -1, param);
  const std::size_t r = t.size() - 1;
  for (auto& s : t.slot) s[r] = in.get<double>();
  t.F_n[r] = in.get<double>();
  t.F_t[r] = in.get<double>();
  if (t.has_moment()) t.M1[r] = in.get<double>(), t.M2[r] = in.get<double>();
  t.f1[r] = in.get<Vec2>();
}

// Bytes of one row record of `t`.
inline std::size_t row_bytes(const ContactTable& t) {
  return sizeof(ContactKey) + sizeof(std::int32_t) + sizeof(double) * (t.slot.size() + 2 + (t.has_moment() ? 2 : 0)) +
         sizeof(Vec2);
}

}  // namespace rondel
