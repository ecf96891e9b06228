#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
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

// One row per candidate pair (within the interaction range plus skin), structure of arrays, rows in
// ascending key order. History slots exist only for the laws selected (their names come from the laws).
// The force columns hold this step's result for the per-disc sums and the previous step's scalars for the
// trapezoidal work of the energy ledger.
class ContactTable {
 public:
  ContactTable() = default;
  ContactTable(std::vector<std::string> slot_names, bool has_moment);

  std::vector<ContactKey> key;
  std::vector<std::int32_t> i1, i2;       // local disc indices (a wall row: i2 is the wall index)
  std::vector<std::int32_t> param;        // index into the parameter table
  std::vector<std::vector<double>> slot;  // history, slot[k][row]
  std::vector<double> F_n, F_t;           // scalars of the last evaluation
  std::vector<double> M1, M2;             // rolling couples on disc 1 and 2 (only with a rolling law)
  std::vector<Vec2> f1;                   // force on disc 1 (disc 2 gets -f1)
  std::vector<double> tq1, tq2;           // torques on disc 1 and disc 2

  std::size_t size() const { return key.size(); }
  const std::vector<std::string>& slot_names() const { return slot_names_; }
  bool has_moment() const { return has_moment_; }
  void clear();
  std::size_t memory_bytes() const;

  // Appends a row with zero history.
  void push(ContactKey k, std::int32_t a, std::int32_t b, std::int32_t p);
  // Appends row r of `src` (same columns) with its key, parameter index, history and last scalars; the
  // local indices are set to -1 (they are rebuilt).
  void push_copy(const ContactTable& src, std::size_t r);
  // Sorts rows by key and keeps the first of equal keys (copies of one contact are bit-identical).
  void sort_unique_by_key();
  // True when the row carries state worth keeping (history or last forces).
  bool has_state(std::size_t r) const;
  // Copies history and last scalars, matched by key, from `old` (both tables in ascending key order).
  // Rows of `old` that are not candidates any more are dropped: their contact has opened.
  void inherit_history(const ContactTable& old);

 private:
  std::vector<std::string> slot_names_;
  bool has_moment_ = false;
};

}  // namespace rondel
