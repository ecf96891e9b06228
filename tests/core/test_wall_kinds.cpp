// The wall kinds' registry (core/WallKinds.hpp): every kind's code, name and file round trip, each kind's
// proximity is its formula, and a code that no kind has is no kind (the file reader refuses it:
// tests/parallel/test_wall_kinds_file.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "core/WallKinds.hpp"

namespace rondel {
namespace {

TEST(WallKinds, EveryKindHasItsOwnCodeNameAndKey) {
  std::set<std::string> names, keys;
  std::set<long> codes;
  WallKinds::each([&]<class K>() {
    EXPECT_TRUE(names.insert(K::name).second) << K::name << " twice";
    EXPECT_TRUE(keys.insert(K::key).second) << K::key << " twice";
    EXPECT_TRUE(codes.insert(static_cast<long>(K::kind)).second) << K::name;
    EXPECT_EQ(WallKinds::from_code(static_cast<long>(K::kind)), K::kind) << K::name;
    EXPECT_STREQ(WallKinds::name(K::kind), K::name);
    EXPECT_EQ(WallKinds::names_by_code().at(static_cast<std::size_t>(K::kind)), K::name);
  });
  EXPECT_EQ(names.size(), WallKinds::size);
  EXPECT_EQ(WallKinds::names_by_code().size(), WallKinds::size) << "the codes are 0 .. size - 1";
  EXPECT_FALSE(WallKinds::from_code(static_cast<long>(WallKinds::size)).has_value());
  EXPECT_FALSE(WallKinds::from_code(-1).has_value());
  EXPECT_STREQ(WallKinds::name(static_cast<Wall::Kind>(WallKinds::size)), "unknown");
}

TEST(WallKinds, ProximityIsEachKindsFormula) {
  const Domain domain{0.0, 1.0, 0.0, 1.0, false, false};
  const Wall line = WallLine::read({0.0, 0.1, 0.0, 2.0}, domain);  // y = 0.1, normal +y
  const Wall segment = WallSegment::read({0.2, 0.0, 0.6, 0.0}, domain);
  const Wall circle = WallCircle::read({0.5, 0.5, 0.4}, domain);
  const Vec2 x{0.3, 0.35};
  EXPECT_DOUBLE_EQ(line.proximity(x).dist, 0.25);
  EXPECT_EQ(line.proximity(x).n.y, -1.0);
  EXPECT_DOUBLE_EQ(segment.proximity(x).dist, 0.35);
  EXPECT_DOUBLE_EQ(segment.proximity({0.0, 0.0}).dist, 0.2) << "beyond an end: the distance to the end";
  EXPECT_DOUBLE_EQ(circle.proximity(x).dist, 0.4 - std::hypot(0.2, 0.15));
  EXPECT_LT(circle.proximity({0.95, 0.5}).dist, 0.0) << "outside the circle";
  EXPECT_NE(WallLine::behind(line, -0.01), "") << "behind a line";
  EXPECT_EQ(WallSegment::behind(segment, -0.01), "") << "a segment has no far side";
  EXPECT_NE(WallCircle::behind(circle, -0.01), "");
}

}  // namespace
}  // namespace rondel
