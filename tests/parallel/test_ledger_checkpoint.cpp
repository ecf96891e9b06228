// A checkpoint's ledger and contact rows round-trip (FORMAT.md): every ledger term written lands under
// its own /ledger attribute (checked against the format's names, listed here on their own) and reads back
// into the same field; every record column of the contact rows comes back in its dataset, in key order,
// on any rank count, with the local indices unset and the torques zero. Rows without state and rows the
// rank does not book (disc 1 a ghost) are not written.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "../support/ContactRows.hpp"
#include "../support/TempDir.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/LedgerTerms.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {
namespace {

// A file path in a directory made by rank 0 and known to every rank (removed by rank 0 at the end).
class SharedFile {
 public:
  SharedFile(const Communicator& comm, const std::string& name) : comm_(comm) {
    if (comm.root()) dir_ = std::make_unique<test::TempDir>("rondel-ledger");
    const std::string path = comm.root() ? (dir_->path() / name).string() : std::string();
    std::vector<char> bytes(path.begin(), path.end());
    comm.broadcast(bytes);
    path_.assign(bytes.begin(), bytes.end());
  }
  ~SharedFile() { comm_.barrier(); }
  const std::string& path() const { return path_; }

 private:
  const Communicator& comm_;
  std::unique_ptr<test::TempDir> dir_;
  std::string path_;
};

// The value of column number `c` of the row with key k: the same on every rank, none zero.
double column_value(ContactKey k, int c) { return 1000.0 * k.lo + k.hi + 0.125 * c; }

void fill_row(ContactTable& t, std::size_t r) { test::fill_row(t, r, column_value, kColumnRecord); }

// Row r read back: its record columns are what fill_row wrote, its local indices unset, its torques zero.
void expect_read_row(const ContactTable& t, std::size_t r) {
  ContactTable written = t.empty_like();
  written.push(t.key[r], -1, -1, 0);
  fill_row(written, 0);
  EXPECT_EQ(test::row_text(t, r), test::row_text(written, 0));
}

struct Written {
  StateHeader header;
  DiscStore discs;
  ContactTable pairs = ContactTable({"xi", "theta_r"}, 1), walls = ContactTable({"xi", "theta_r"}, 1, true);
};

// Rank r owns disc r + 1 and books two pair rows and one wall row of it; it also holds a row without state
// and a row whose disc 1 is a ghost, neither written.
Written make_state(const Communicator& comm) {
  Written w;
  const std::int64_t me = comm.rank() + 1;
  w.discs.add(me, 0, 0.5, 1.0, 1.0, Vec2{static_cast<double>(me), 0.0});
  for (std::int64_t hi : {me + 10, me + 20}) w.pairs.push({me, hi}, 0, 1, 0);
  w.pairs.push({me, me + 30}, 0, 1, 0);  // no state
  w.pairs.push({me, me + 40}, 1, 0, 0);  // booked by the rank owning its disc 1
  w.walls.push({me, 0}, 0, 0, 0);
  for (std::size_t r : {0u, 1u, 3u}) fill_row(w.pairs, r);
  fill_row(w.walls, 0);
  w.header.kind = "checkpoint";
  w.header.slots = w.pairs.slot_names();
  double v = 0.5;
  w.header.ledger.for_each_term([&v](const LedgerTermInfo&, double& value) { value = (v += 1.0); });
  return w;
}

TEST(LedgerCheckpoint, EveryTermRoundTripsThroughItsOwnAttribute) {
  const Communicator comm;
  const SharedFile file(comm, "state.h5");
  Written w = make_state(comm);
  write_state_file(file.path(), w.header, w.discs, w.pairs, w.walls, WallSet{}, comm, {}, 0.0);
  const StateHeader back = read_state_header(file.path(), comm);
  LedgerTerms::visit_terms(
      [](const LedgerTermInfo& t, double written, double read) { EXPECT_EQ(read, written) << t.name; }, w.header.ledger,
      back.ledger);
  // The format's attribute names, each with the field it holds.
  const std::vector<std::pair<std::string, double LedgerTerms::*>> format = {{"KE0", &LedgerTerms::KE0},
                                                                             {"W_g", &LedgerTerms::W_g},
                                                                             {"W_w", &LedgerTerms::W_w},
                                                                             {"W_n", &LedgerTerms::W_n},
                                                                             {"W_t", &LedgerTerms::W_t},
                                                                             {"W_r", &LedgerTerms::W_r},
                                                                             {"D_slip", &LedgerTerms::D_slip},
                                                                             {"D_r_plastic", &LedgerTerms::D_r_plastic},
                                                                             {"D_r_dashpot", &LedgerTerms::D_r_dashpot},
                                                                             {"E_r_break", &LedgerTerms::E_r_break},
                                                                             {"D_damping", &LedgerTerms::D_damping},
                                                                             {"scale", &LedgerTerms::scale}};
  const Hdf5File f(file.path(), Hdf5File::Mode::read, comm);
  for (const auto& [name, field] : format)
    EXPECT_EQ(f.read_double_attribute("/ledger", name), w.header.ledger.*field) << name;
}

// A checkpoint written before the local damping has no /ledger/D_damping: it reads as 0, the other terms as
// written (the attribute is removed here with the HDF5 library itself, as an older writer would have left it).
TEST(LedgerCheckpoint, OlderCheckpointWithoutDDampingReadsItAsZero) {
  const Communicator comm;
  const SharedFile file(comm, "older.h5");
  Written w = make_state(comm);
  ASSERT_NE(w.header.ledger.D_damping, 0.0);
  write_state_file(file.path(), w.header, w.discs, w.pairs, w.walls, WallSet{}, comm, {}, 0.0);
  comm.barrier();
  if (comm.root()) {
    const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    const hid_t f = H5Fopen(file.path().c_str(), H5F_ACC_RDWR, fapl);
    ASSERT_GE(f, 0);
    EXPECT_GE(H5Adelete_by_name(f, "/ledger", "D_damping", H5P_DEFAULT), 0);
    // Such a writer wrote format version 3, without the attributes' checksum of version 4.
    EXPECT_GE(H5Adelete_by_name(f, "/integrity", "attributes_checksum", H5P_DEFAULT), 0);
    const hid_t version = H5Aopen_by_name(f, "/", "format_version", H5P_DEFAULT, H5P_DEFAULT);
    const std::int64_t three = 3;
    EXPECT_GE(H5Awrite(version, H5T_NATIVE_INT64, &three), 0);
    H5Aclose(version);
    H5Fclose(f);
    H5Pclose(fapl);
  }
  comm.barrier();
  {
    const Hdf5File f(file.path(), Hdf5File::Mode::read, comm);
    EXPECT_FALSE(f.has_attribute("/ledger", "D_damping")) << "the attribute was not removed";
  }
  const StateHeader back = read_state_header(file.path(), comm);
  LedgerTerms::visit_terms(
      [](const LedgerTermInfo& t, double written, double read) {
        if (t.name == "D_damping")
          EXPECT_EQ(read, 0.0);
        else
          EXPECT_EQ(read, written) << t.name;
      },
      w.header.ledger, back.ledger);
}

TEST(LedgerCheckpoint, ContactRowsRoundTripColumnByColumn) {
  const Communicator comm;
  const SharedFile file(comm, "rows.h5");
  Written w = make_state(comm);
  write_state_file(file.path(), w.header, w.discs, w.pairs, w.walls, WallSet{}, comm, {}, 0.0);
  ContactTable pairs({"xi", "theta_r"}, true), walls({"xi", "theta_r"}, true);
  read_state_rows(file.path(), pairs, walls, comm);
  EXPECT_EQ(comm.sum(static_cast<std::int64_t>(pairs.size())), 2 * comm.size());
  EXPECT_EQ(comm.sum(static_cast<std::int64_t>(walls.size())), comm.size());
  for (const ContactTable* t : {&pairs, &walls}) {
    for (std::size_t r = 0; r < t->size(); ++r) {
      EXPECT_TRUE(r == 0 || t->key[r - 1] < t->key[r]) << "rows in ascending key order";
      const std::int64_t gap = t->key[r].hi - t->key[r].lo;
      EXPECT_TRUE(t == &walls ? t->key[r].hi == 0 : gap == 10 || gap == 20) << "only the booked rows with state";
      expect_read_row(*t, r);
    }
  }
}

}  // namespace
}  // namespace rondel
