#pragma once
// The kinds of walls (docs/developing.md, "How to add a wall kind"): one type per value of Wall::Kind, each in its
// own file (WallLine.hpp, WallSegment.hpp, WallCircle.hpp), listed once in `WallKinds`. A kind declares its name,
// the configuration key of its records and their help, how to make a wall from a record, the closest point of the
// wall to a disc, which side of it a disc may not start on, and the piece of it ParaView draws. The checkpoint,
// the snapshots and the Python reader share the list: /walls/kind holds the Wall::Kind value, and the attribute
// /walls/kind_names the names in value order (FORMAT.md), which tools/rondel/h5.py decodes the values with.
#include <optional>
#include <string>
#include <vector>

#include "core/Domain.hpp"
#include "core/Wall.hpp"
#include "core/WallCircle.hpp"
#include "core/WallLine.hpp"
#include "core/WallSegment.hpp"

namespace rondel {

template <class... Kinds>
struct WallKindList {
  static constexpr std::size_t size = sizeof...(Kinds);
  // Calls f.template operator()<K>() for the kind of `kind`; false when none is (a value no kind has).
  template <class F>
  static bool with(Wall::Kind kind, F&& f) {
    return ((kind == Kinds::kind ? (f.template operator()<Kinds>(), true) : false) || ...);
  }
  // Calls f.template operator()<K>() for every kind, in the list's order.
  template <class F>
  static void each(F&& f) {
    (f.template operator()<Kinds>(), ...);
  }
  static const char* name(Wall::Kind kind) {
    const char* out = "unknown";
    with(kind, [&out]<class K>() { out = K::name; });
    return out;
  }
  // The kind of the value `code` of a file (/walls/kind); none for a value no kind has.
  static std::optional<Wall::Kind> from_code(long code) {
    std::optional<Wall::Kind> out;
    each([&]<class K>() {
      if (static_cast<long>(K::kind) == code) out = K::kind;
    });
    return out;
  }
  // The names in the order of the Wall::Kind values (the attribute /walls/kind_names).
  static std::vector<std::string> names_by_code() {
    std::vector<std::string> out(size);
    each([&out]<class K>() { out.at(static_cast<std::size_t>(K::kind)) = K::name; });
    return out;
  }
  static Wall::Proximity proximity(const Wall& w, Vec2 x) {
    Wall::Proximity out{0.0, {}};
    with(w.kind, [&]<class K>() { out = K::proximity(w, x); });
    return out;
  }
};

// The registry rows, in the order their walls are numbered (the records of each key, then the box walls).
using WallKinds = WallKindList<WallLine, WallSegment, WallCircle>;

}  // namespace rondel
