#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/Vec2.hpp"

namespace rondel {

// Key of a contact row in its canonical frame: (lower gid, higher gid), or (disc gid, wall id).
struct ContactKey {
  std::int64_t lo = 0;
  std::int64_t hi = 0;
  friend bool operator<(const ContactKey& a, const ContactKey& b) {
    return a.lo < b.lo || (a.lo == b.lo && a.hi < b.hi);
  }
  friend bool operator==(const ContactKey& a, const ContactKey& b) { return a.lo == b.lo && a.hi == b.hi; }
};

// A row to be: its key and local disc (or wall) indices, as the neighbour search finds it.
struct RowCandidate {
  ContactKey key;
  std::int32_t i1 = 0, i2 = 0;
};

// What each contact-table column is used for. Every operation on whole rows (push, copy, inheritance by
// key, migration records, checkpoints, memory accounting) loops over the column table below instead of
// naming columns one by one, so a new column is one line there.
enum ContactColumnUse : unsigned {
  kColumnRecord = 1u,      // in a row record: travels with migration, written to and read from checkpoints
  kColumnInherit = 2u,     // copied by key from the old table when the table is rebuilt
  kColumnState = 4u,       // nonzero means the row carries state worth keeping (has_state)
  kColumnLocalIndex = 8u,  // a local disc or wall index: -1 in a copied or read row until it is rebuilt
};

// The value a column not carried by a record takes in a copied or read row: -1 for a local index (not
// known yet), zero otherwise.
template <class T>
T unset_column_value(unsigned uses) {
  if constexpr (std::is_integral_v<T>) return (uses & kColumnLocalIndex) ? T{-1} : T{0};
  return T{};
}

// One row per candidate pair (within the interaction range plus skin), structure of arrays, rows in
// ascending key order: the contact kernel adds each row's force to its discs' sums in row order, which is
// the order of ascending partner gid for every disc (docs/design.md section 5). History slots exist only for
// the laws selected (their names come from the laws), the rolling couples only with a rolling law: M1 alone
// for a law whose couple on disc 2 is -M1 (every objective law), M1 and M2 for a law that gives each disc a
// couple of its own. The scalars are those of the last evaluation: the state of the spring-sliders and the
// previous step's values for the trapezoidal work of the energy ledger. Wall rows also keep the force on
// the disc, f1, for the wall's work and load (a pair's force follows from F_n, F_t and the geometry).
class ContactTable {
 public:
  ContactTable() = default;
  // couples: the rolling couple columns, 0 (no rolling law), 1 (M1) or 2 (M1 and M2); wall_rows: a table of
  // disc-wall rows (with the column f1).
  ContactTable(std::vector<std::string> slot_names, int couples, bool wall_rows = false);
  // The table of parallel bonds (docs/physics.md section 12): pair rows keyed like their contacts whose columns are
  // the bond's state, history/Fb_n, history/Fb_s and history/Mb, and no last scalars. Every row is state: a bond
  // is kept until it breaks, whatever its discs' distance (physics/BondPass.hpp).
  static ContactTable bond_table();

  std::vector<ContactKey> key;
  std::vector<std::int32_t> i1, i2;       // local disc indices (a wall row: i2 is the wall index)
  std::vector<std::int32_t> param;        // index into the parameter table
  std::vector<std::vector<double>> slot;  // history, slot[k][row]
  std::vector<double> F_n, F_t;           // scalars of the last evaluation
  std::vector<double> M1, M2;             // rolling couples on disc 1 and 2 (see couples())
  std::vector<Vec2> f1;                   // force on disc 1 (wall rows only)

  std::size_t size() const { return key.size(); }
  const std::vector<std::string>& slot_names() const { return slot_names_; }
  // The rolling couple columns: 0, 1 (M1; the couple on disc 2 is -M1) or 2 (M1 and M2).
  int couples() const { return couples_; }
  bool wall_rows() const { return wall_rows_; }
  bool bonds() const { return bonds_; }
  // An empty table with the same columns.
  ContactTable empty_like() const {
    ContactTable t(slot_names_, couples_, wall_rows_);
    t.bonds_ = bonds_;
    return t;
  }
  void reserve(std::size_t rows);
  void clear();
  std::size_t memory_bytes() const;

  // Appends a row with zero history.
  void push(ContactKey k, std::int32_t a, std::int32_t b, std::int32_t p);
  // Appends row r of `src` (same columns) with every column but the local indices, which are set to -1
  // (they are rebuilt).
  void push_copy(const ContactTable& src, std::size_t r);
  // Sorts rows by key and keeps the first of equal keys (copies of one contact are bit-identical).
  void sort_unique_by_key();
  // True when the row carries state worth keeping (history or last forces; every row of a bond table).
  bool has_state(std::size_t r) const;
  // Copies history and last forces, matched by key, from `old` (both tables in ascending key order).
  // Rows of `old` that are not candidates any more are dropped: their contact has opened.
  void inherit_history(const ContactTable& old);
  // Replaces the rows by `found` (ascending keys; emptied and freed here), each new row taking the kept columns
  // (kColumnInherit) of the row of its key held now, the other columns zero (param too: the caller sets it). One
  // column at a time, each old column freed as soon as its successor is filled, so that the peak is the kept
  // columns, `found` and the new keys and indices instead of two whole tables (docs/scaling.md, "Memory of a run").
  void replace_rows(std::vector<RowCandidate>& found);

  // Visits every column present, in the checkpoint's order, with its name (the dataset name under the
  // contact group, "history/<slot>" for a slot), its uses and that column of each of `tables` (tables of
  // the same layout as the first): visit(name, uses, column_of_tables...).
  template <class Visitor, class... Tables>
  static void visit_columns(Visitor&& visit, Tables&... tables) {
    const ContactTable& first = first_of(tables...);
    visit(std::string_view("key"), kColumnRecord, tables.key...);
    visit(std::string_view("i1"), kColumnLocalIndex, tables.i1...);
    visit(std::string_view("i2"), kColumnLocalIndex, tables.i2...);
    visit(std::string_view("param"), kColumnRecord, tables.param...);
    constexpr unsigned kKept = kColumnRecord | kColumnInherit | kColumnState;
    for (std::size_t k = 0; k < first.slot.size(); ++k)
      visit(std::string_view(first.slot_columns_[k]), kKept, tables.slot[k]...);
    if (first.bonds_) return;
    visit(std::string_view("F_n"), kKept, tables.F_n...);
    visit(std::string_view("F_t"), kKept, tables.F_t...);
    if (first.couples_ > 0) visit(std::string_view("M1"), kKept, tables.M1...);
    if (first.couples_ > 1) visit(std::string_view("M2"), kKept, tables.M2...);
    // The last force only feeds the wall-work trapezoid and the wall's load: it is kept, but is no state by
    // itself.
    if (first.wall_rows_) visit(std::string_view("f1"), kColumnRecord | kColumnInherit, tables.f1...);
  }
  template <class Visitor>
  void for_each_column(Visitor&& visit) {
    visit_columns(visit, *this);
  }
  template <class Visitor>
  void for_each_column(Visitor&& visit) const {
    visit_columns(visit, *this);
  }

 private:
  template <class First, class... Rest>
  static const ContactTable& first_of(First& t, Rest&...) {
    return t;
  }

  std::vector<std::string> slot_names_;
  std::vector<std::string> slot_columns_;  // "history/<slot>", the slots' column names
  std::uint8_t couples_ = 0;
  bool wall_rows_ = false;
  bool bonds_ = false;
};

}  // namespace rondel
