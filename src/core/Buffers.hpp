#pragma once
// The two things done to large buffers in many places: grow one that is reused without doubling it, and give one's
// memory back (clear() keeps the capacity, and shrink_to_fit may keep it too).
#include <cstddef>
#include <type_traits>
#include <vector>

namespace rondel {

// Resizes a reused buffer: when it must grow, to n and 1/16 more (not the doubling of push_back and resize), so that
// its capacity stays near what one use needs and later ones fit.
template <class T>
void resize_buffer(std::vector<T>& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(n + n / 16);
  v.resize(n);
}

// Frees the memory of each of the vectors given.
template <class... V>
void release(V&... v) {
  (std::decay_t<V>().swap(v), ...);
}

}  // namespace rondel
