#include "core/DiscStore.hpp"

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <type_traits>

namespace rondel {

std::size_t DiscStore::add(std::int64_t id, std::int32_t mat, double R, double density, double thickness, Vec2 x,
                           Vec2 v, double w) {
  if (n_ghost() != 0) throw std::logic_error("DiscStore::add with ghosts present");
  const double m = density * std::numbers::pi * R * R * thickness;
  gid.push_back(id);
  material.push_back(mat);
  radius.push_back(R);
  mass.push_back(m);
  inertia.push_back(0.5 * m * R * R);
  position.push_back(x);
  velocity.push_back(v);
  theta.push_back(0.0);
  omega.push_back(w);
  force.push_back({});
  torque.push_back(0.0);
  flags.push_back(0u);
  return n_owned_++;
}

std::size_t DiscStore::add(std::int64_t id, std::int32_t mat, double R, const Material& m, Vec2 x, Vec2 v, double w) {
  const std::size_t i = add(id, mat, R, m.density, m.thickness, x, v, w);
  set_material(i, mat, m);
  return i;
}

void DiscStore::set_material(std::size_t i, std::int32_t mat, const Material& m) {
  material[i] = mat;
  mass[i] = m.mass(radius[i]);
  inertia[i] = m.inertia(mass[i], radius[i]);
}

void DiscStore::reserve(std::size_t n) {
  for_each_field([n](const char*, unsigned, auto& field) { field.reserve(n); });
}

void DiscStore::clear() {
  for_each_field([](const char*, unsigned, auto& field) { field.clear(); });
  n_owned_ = 0;
}

void DiscStore::truncate_to_owned() {
  const std::size_t n = n_owned_;
  for_each_field([n](const char*, unsigned, auto& field) { field.resize(n); });
}

void DiscStore::remove_owned(const std::vector<bool>& drop) {
  truncate_to_owned();
  // The discs before the first dropped one stay where they are (all of them, most often: nothing is copied).
  std::size_t first = 0;
  while (first < n_owned_ && !drop[first]) ++first;
  if (first == n_owned_) return;
  std::size_t kept = 0;
  for_each_field([&drop, &kept, first](const char*, unsigned, auto& field) {
    std::size_t out = first;
    for (std::size_t i = first; i < field.size(); ++i)
      if (!drop[i]) field[out++] = field[i];
    field.resize(out);
    kept = out;
  });
  n_owned_ = kept;
}

bool DiscStore::sort_owned_by_gid() {
  const std::size_t n = n_owned_;
  if (std::is_sorted(gid.begin(), gid.begin() + static_cast<std::ptrdiff_t>(n))) return false;
  truncate_to_owned();
  std::vector<std::uint32_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [this](std::uint32_t a, std::uint32_t b) { return gid[a] < gid[b]; });
  for_each_field([&order](const char*, unsigned, auto& field) {
    auto sorted = field;
    for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = field[order[k]];
    field.swap(sorted);
  });
  return true;
}

std::size_t DiscStore::memory_bytes() const {
  std::size_t bytes = 0;
  const_cast<DiscStore*>(this)->for_each_field(
      [&bytes](const char*, unsigned, auto& field) { bytes += field.capacity() * sizeof(field[0]); });
  return bytes;
}

namespace {
// How a file stores an element of type T.
template <class T>
DiscFieldInfo stored_as(const char* name) {
  if constexpr (std::is_same_v<T, Vec2>)
    return {name, "Float", 8, 2};
  else if constexpr (std::is_floating_point_v<T>)
    return {name, "Float", sizeof(T), 1};
  else if constexpr (std::is_signed_v<T>)
    return {name, "Int", sizeof(T), 1};
  else
    return {name, "UInt", sizeof(T), 1};
}
}  // namespace

std::vector<DiscFieldInfo> snapshot_fields() {
  std::vector<DiscFieldInfo> out;
  DiscStore().for_each_field([&out](const char* name, unsigned, auto& field) {
    out.push_back(stored_as<typename std::decay_t<decltype(field)>::value_type>(name));
  });
  out.push_back(stored_as<std::int32_t>(kRankField));
  return out;
}

std::vector<std::string> snapshot_field_names() {
  std::vector<std::string> out;
  for (const DiscFieldInfo& f : snapshot_fields()) out.push_back(f.name);
  return out;
}

}  // namespace rondel
