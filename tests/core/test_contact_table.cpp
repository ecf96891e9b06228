// ContactTable (docs/design.md section 2): rows keyed by (lo gid, hi gid), columns declared once in its column
// table. Push, clear, sorting, inheritance of history by key, copies, the state test and the memory
// accounting on small tables with and without the rolling columns and history slots; the row records of
// migration and checkpoints (parallel/RecordPacking.hpp, header-only) carry exactly the record columns; and a
// member added to the table without a line in the column table fails here.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "../support/ContactRows.hpp"
#include "core/ContactTable.hpp"
#include "parallel/RecordPacking.hpp"

namespace rondel {
namespace {

ContactTable rolling_table() { return ContactTable({"xi", "x_r"}, 1); }
// A rolling law of its own couples (force_proportional), with wall rows (the column f1).
ContactTable own_couples_wall_table() { return ContactTable({"xi"}, 2, true); }

// Every column of row r (but the key) set to values that depend on the row and the column, none zero.
void fill_row(ContactTable& t, std::size_t r) {
  test::fill_row(t, r, [r](ContactKey, int c) { return 8.0 + 80.0 * static_cast<double>(r) + c; });
}

using test::row_text;

std::vector<std::string> column_names(const ContactTable& t) {
  std::vector<std::string> names;
  t.for_each_column([&](std::string_view name, unsigned, const auto&) { names.emplace_back(name); });
  return names;
}

// Every column has one entry per row.
void expect_consistent(const ContactTable& t) {
  t.for_each_column([&](std::string_view name, unsigned, const auto& column) {
    EXPECT_EQ(column.size(), t.size()) << "column " << name;
  });
}

TEST(ContactTable, ColumnsPresentFollowTheLaws) {
  EXPECT_EQ(column_names(ContactTable()), (std::vector<std::string>{"key", "i1", "i2", "param", "F_n", "F_t"}));
  EXPECT_EQ(column_names(rolling_table()),
            (std::vector<std::string>{"key", "i1", "i2", "param", "history/xi", "history/x_r", "F_n", "F_t", "M1"}));
  EXPECT_EQ(column_names(own_couples_wall_table()),
            (std::vector<std::string>{"key", "i1", "i2", "param", "history/xi", "F_n", "F_t", "M1", "M2", "f1"}));
}

TEST(ContactTable, PushAppendsAZeroRowAndClearEmptiesEveryColumn) {
  for (ContactTable t : {ContactTable(), rolling_table(), own_couples_wall_table()}) {
    t.push({1, 2}, 0, 1, 3);
    t.push({1, 5}, 0, 4, 2);
    ASSERT_EQ(t.size(), 2u);
    expect_consistent(t);
    EXPECT_EQ(t.key[1], (ContactKey{1, 5}));
    EXPECT_EQ(t.i1[1], 0);
    EXPECT_EQ(t.i2[1], 4);
    EXPECT_EQ(t.param[1], 2);
    EXPECT_FALSE(t.has_state(0));
    EXPECT_FALSE(t.has_state(1));
    t.clear();
    EXPECT_EQ(t.size(), 0u);
    expect_consistent(t);
    EXPECT_EQ(t.slot.size(), t.slot_names().size()) << "clear keeps the slots";
  }
}

TEST(ContactTable, HasStateLooksAtHistoryAndLastScalarsOnly) {
  ContactTable t = own_couples_wall_table();
  t.push({1, 2}, 0, 1, 0);
  t.f1[0] = {1.0, 2.0};  // the last force alone is no state (it only feeds the wall-work trapezoid)
  EXPECT_FALSE(t.has_state(0));
  for (auto* column : {&t.slot[0], &t.F_n, &t.F_t, &t.M1, &t.M2}) {
    (*column)[0] = -1e-300;
    EXPECT_TRUE(t.has_state(0));
    (*column)[0] = 0.0;
  }
  EXPECT_FALSE(t.has_state(0));
}

TEST(ContactTable, SortUniqueByKeyKeepsTheFirstOfEqualKeysWithAllItsColumns) {
  for (const ContactTable& empty : {ContactTable({"xi"}, 0), rolling_table(), own_couples_wall_table()}) {
    ContactTable t = empty;
    const std::vector<ContactKey> keys = {{3, 4}, {1, 9}, {1, 2}, {3, 4}, {2, 3}};
    for (std::size_t r = 0; r < keys.size(); ++r) {
      t.push(keys[r], 0, 0, 0);
      fill_row(t, r);
    }
    std::vector<std::string> expected = {row_text(t, 2), row_text(t, 1), row_text(t, 4), row_text(t, 0)};
    t.sort_unique_by_key();
    ASSERT_EQ(t.size(), 4u);
    expect_consistent(t);
    for (std::size_t r = 0; r < t.size(); ++r) EXPECT_EQ(row_text(t, r), expected[r]) << "row " << r;
  }
}

TEST(ContactTable, PushCopyCopiesEveryColumnButTheLocalIndices) {
  ContactTable src = own_couples_wall_table();
  src.push({1, 2}, 5, 6, 0);
  fill_row(src, 0);
  ContactTable t = src.empty_like();
  t.push_copy(src, 0);
  expect_consistent(t);
  EXPECT_EQ(row_text(t, 0, ~kColumnLocalIndex), row_text(src, 0, ~kColumnLocalIndex));
  EXPECT_EQ(t.i1[0], -1);
  EXPECT_EQ(t.i2[0], -1);
}

TEST(ContactTable, InheritHistoryCopiesTheKeptColumnsOfMatchingKeys) {
  ContactTable old = own_couples_wall_table();
  for (ContactKey k : {ContactKey{1, 2}, ContactKey{1, 3}, ContactKey{2, 5}}) old.push(k, 0, 0, 0);
  for (std::size_t r = 0; r < old.size(); ++r) fill_row(old, r);
  ContactTable t = old.empty_like();
  t.push({1, 3}, 7, 8, 1);
  t.push({2, 4}, 7, 9, 1);
  t.push({2, 5}, 8, 9, 2);
  t.inherit_history(old);
  expect_consistent(t);
  EXPECT_EQ(row_text(t, 0, kColumnInherit), row_text(old, 1, kColumnInherit));
  EXPECT_EQ(row_text(t, 2, kColumnInherit), row_text(old, 2, kColumnInherit));
  for (std::size_t r : {0u, 2u})
    EXPECT_EQ(t.param[r], r == 0 ? 1 : 2) << "the parameter index comes from the new build";
  EXPECT_FALSE(t.has_state(1)) << "a new candidate starts without history";
  EXPECT_EQ(t.i1[2], 8);
}

TEST(ContactTable, ReplaceRowsTakesTheFoundRowsWithTheKeptColumnsOfTheirKeys) {
  ContactTable t = own_couples_wall_table();
  for (ContactKey k : {ContactKey{1, 2}, ContactKey{1, 3}, ContactKey{2, 5}, ContactKey{4, 6}}) t.push(k, 3, 4, 5);
  for (std::size_t r = 0; r < t.size(); ++r) fill_row(t, r);
  const ContactTable old = t;
  std::vector<RowCandidate> found = {{{0, 9}, 1, 2}, {{1, 3}, 7, 8}, {{2, 4}, 7, 9}, {{4, 6}, 8, 9}};
  t.replace_rows(found);
  expect_consistent(t);
  EXPECT_TRUE(found.empty());
  EXPECT_EQ(found.capacity(), 0u) << "the candidates are freed before the kept columns are copied";
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(row_text(t, 1, kColumnInherit), row_text(old, 1, kColumnInherit));
  EXPECT_EQ(row_text(t, 3, kColumnInherit), row_text(old, 3, kColumnInherit));
  EXPECT_FALSE(t.has_state(0)) << "a key before every old one starts without history";
  EXPECT_FALSE(t.has_state(2)) << "a new key between old ones starts without history";
  for (std::size_t r = 0; r < t.size(); ++r) {
    EXPECT_EQ(t.key[r], (std::vector<ContactKey>{{0, 9}, {1, 3}, {2, 4}, {4, 6}}[r]));
    EXPECT_EQ(t.i1[r], r == 0 ? 1 : (r == 3 ? 8 : 7));
    EXPECT_EQ(t.param[r], 0) << "the parameter index is the caller's to set";
  }
  // The same rows as a table built row by row and given the history by inherit_history.
  ContactTable built = old.empty_like();
  for (ContactKey k : {ContactKey{0, 9}, ContactKey{1, 3}, ContactKey{2, 4}, ContactKey{4, 6}}) built.push(k, 0, 0, 0);
  built.inherit_history(old);
  for (std::size_t r = 0; r < t.size(); ++r)
    EXPECT_EQ(row_text(t, r, kColumnInherit), row_text(built, r, kColumnInherit));
}

TEST(ContactTable, MemoryBytesCountsEveryColumnsCapacity) {
  for (const ContactTable& empty :
       {ContactTable(), ContactTable({"xi"}, 0), rolling_table(), own_couples_wall_table()}) {
    ContactTable t = empty;
    for (std::int64_t k = 0; k < 5; ++k) t.push({k, k + 1}, 0, 0, 0);
    EXPECT_EQ(t.M1.size(), t.couples() > 0 ? 5u : 0u);
    EXPECT_EQ(t.M2.size(), t.couples() > 1 ? 5u : 0u);
    EXPECT_EQ(t.f1.size(), t.wall_rows() ? 5u : 0u);
    std::size_t expected = t.key.capacity() * sizeof(ContactKey) + t.f1.capacity() * sizeof(Vec2);
    for (const auto* c : {&t.i1, &t.i2, &t.param}) expected += c->capacity() * sizeof(std::int32_t);
    for (const auto* c : {&t.F_n, &t.F_t, &t.M1, &t.M2}) expected += c->capacity() * sizeof(double);
    for (const auto& s : t.slot) expected += s.capacity() * sizeof(double);
    EXPECT_EQ(t.memory_bytes(), expected);
  }
}

TEST(ContactTable, RowRecordCarriesExactlyTheRecordColumns) {
  for (const ContactTable& empty : {ContactTable(), rolling_table(), own_couples_wall_table()}) {
    ContactTable t = empty;
    t.push({4, 7}, 2, 3, 1);
    fill_row(t, 0);
    std::size_t record = 0;
    t.for_each_column([&](std::string_view, unsigned uses, const auto& column) {
      if (uses & kColumnRecord) record += sizeof(column[0]);
    });
    ByteBuffer out;
    pack_row(t, 0, out);
    EXPECT_EQ(out.bytes.size(), record);
    EXPECT_EQ(row_bytes(t), record);
    ContactTable back = empty;
    ByteReader in(out.bytes.data(), out.bytes.size());
    unpack_row(back, in);
    EXPECT_TRUE(in.done());
    expect_consistent(back);
    EXPECT_EQ(row_text(back, 0, kColumnRecord), row_text(t, 0, kColumnRecord));
    EXPECT_EQ(back.i1[0], -1);
    EXPECT_EQ(back.i2[0], -1);
  }
}

// A vector member added to ContactTable changes its size: this fails until the column table (and so every
// row operation) knows the new column.
TEST(ContactTable, EveryMemberIsInTheColumnTable) {
  const ContactTable t({}, 2, true);
  std::size_t columns = 0;
  t.for_each_column([&](std::string_view, unsigned, const auto&) { ++columns; });
  constexpr std::size_t kVector = sizeof(std::vector<double>);
  // The visited columns, the slot vector, the slot names and their column names, and the couples and
  // wall_rows flags (in one padded word).
  EXPECT_EQ(sizeof(ContactTable), (columns + 3) * kVector + alignof(std::vector<double>))
      << "ContactTable has a member that ContactTable::visit_columns does not visit";
}

}  // namespace
}  // namespace rondel
