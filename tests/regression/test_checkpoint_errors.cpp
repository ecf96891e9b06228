// Checkpoint and restart refusals (docs/design.md section 7, FORMAT.md): a missing, truncated, corrupted or
// foreign file, a file of another format version, a checkpoint whose laws or history slots differ from the
// configuration, and an output directory that cannot be written are refused by the Simulation constructor
// (so before any step runs and before any output file is written) with an InputError or ConfigError that
// names the file and says what is wrong. A checkpoint cut short (a leftover .part file, a truncated or
// incomplete newest file) is never picked by --resume: the previous complete one is. The signal path of the real
// executable is test_checkpoint_signal.cpp's.
//
// One rank (the regression binary, MPI initialised by its main).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "app/Checkpointing.hpp"
#include "app/Simulation.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"
#include "support/Assertions.hpp"
#include "support/Quiet.hpp"
#include "support/Restamp.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

using test::QuietCout;
using test::TempDir;

// Discs dropped into a box with a wall moving in from the left, Coulomb friction and a rolling law with
// history (the law block follows contact.rolling).
std::string scene(const std::string& law = "wang") { return test::moving_wall_box_ini(law); }

Config config_for(const fs::path& out, const std::string& law = "wang", std::vector<std::string> more = {}) {
  more.push_back("--run.output=" + out.string());
  return parse_config_text(scene(law), more);
}

// A valid checkpoint after `steps` steps, written into `out`; returns its path.
fs::path make_checkpoint(const fs::path& out, int steps, const std::string& law = "wang") {
  const Communicator self(MPI_COMM_SELF);
  QuietCout quiet;
  Simulation sim(config_for(out, law, {"--run.overwrite=true"}), self, true);
  for (int s = 0; s < steps; ++s) sim.step();
  return sim.write_checkpoint();
}

// Constructs a restart from `file` with `config`; returns the message of the expected error type, or ""
// after recording a failure when the restart is accepted or throws something else.
template <class Error>
std::string restart_refusal(const fs::path& file, Config config) {
  const Communicator self(MPI_COMM_SELF);
  try {
    QuietCout quiet;
    Simulation sim(std::move(config), self, true, file.string());
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "restart from " << file << ": expected "
                  << (std::is_same_v<Error, InputError> ? "InputError" : "ConfigError") << ", got " << typeid(e).name()
                  << ": " << e.what();
    return "";
  }
  ADD_FAILURE() << "the restart from " << file << " was accepted";
  return "";
}

template <class Error>
std::string restart_refusal(const fs::path& file, const fs::path& out, const std::string& law = "wang",
                            const std::vector<std::string>& more = {}) {
  return restart_refusal<Error>(file, config_for(out, law, more));
}

// The same through scene.type = file (a new run whose discs come from `file`).
std::string scene_file_refusal(const fs::path& file, const fs::path& out) {
  const Communicator self(MPI_COMM_SELF);
  try {
    QuietCout quiet;
    Simulation sim(config_for(out, "wang", {"--scene.type=file", "--scene.file=" + file.string()}), self, true);
  } catch (const InputError& e) {
    return e.what();
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "scene.file = " << file << ": got " << typeid(e).name() << ": " << e.what();
    return "";
  }
  ADD_FAILURE() << "scene.file = " << file << " was accepted";
  return "";
}

std::string newest_refusal(const fs::path& dir) {
  try {
    const std::string found = Checkpointing::newest_checkpoint(dir.string(), Communicator(MPI_COMM_SELF));
    ADD_FAILURE() << "newest_checkpoint(" << dir << ") returned " << found;
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void overwrite_bytes(const fs::path& file, std::uintmax_t offset, std::size_t count, char value = 'Z') {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(offset));
  const std::string bytes(count, value);
  f.write(bytes.data(), static_cast<std::streamsize>(count));
}

// HDF5 edits of a closed file (serial access).
struct H5 {
  hid_t file;
  explicit H5(const fs::path& p) : file(H5Fopen(p.string().c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {
    if (file < 0) throw std::runtime_error("cannot open " + p.string());
  }
  ~H5() { H5Fclose(file); }
  void set_int(const char* object, const char* name, std::int64_t v) const {
    // The object held open while its attribute is written (HDF5 1.10 cannot write one opened by path).
    const hid_t o = H5Oopen(file, object, H5P_DEFAULT);
    const hid_t a = H5Aopen(o, name, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_INT64, &v);
    H5Aclose(a);
    H5Oclose(o);
  }
  void remove(const char* object, const char* name) const { H5Adelete_by_name(file, object, name, H5P_DEFAULT); }
  void set_string(const char* object, const char* name, const std::string& v) const {
    if (H5Aexists_by_name(file, object, name, H5P_DEFAULT) > 0) remove(object, name);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, v.size());
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate_by_name(file, object, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, v.data());
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
  }
  haddr_t offset_of(const char* dataset) const {
    const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    const haddr_t at = H5Dget_offset(d);
    H5Dclose(d);
    return at;
  }
  hsize_t storage_of(const char* dataset) const {
    const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    const hsize_t n = H5Dget_storage_size(d);
    H5Dclose(d);
    return n;
  }
};

// A fixture with one valid checkpoint (step 1500, Wang rolling), made once for the suite.
class CheckpointErrors : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("rondel-ckerr");
    valid_ = new fs::path(make_checkpoint(*dir_ / "source", 1500));
  }
  static void TearDownTestSuite() {
    delete valid_;
    delete dir_;
  }
  // A fresh copy of the valid checkpoint.
  fs::path copy(const std::string& name) const {
    const fs::path p = *dir_ / name;
    fs::create_directories(p.parent_path());
    fs::copy_file(*valid_, p, fs::copy_options::overwrite_existing);
    return p;
  }
  fs::path out(const std::string& name) const { return *dir_ / ("out-" + name); }
  static TempDir* dir_;
  static fs::path* valid_;
};
TempDir* CheckpointErrors::dir_ = nullptr;
fs::path* CheckpointErrors::valid_ = nullptr;

TEST_F(CheckpointErrors, TheValidCheckpointRestarts) {
  const Communicator self(MPI_COMM_SELF);
  QuietCout quiet;
  Simulation sim(config_for(out("valid")), self, true, valid_->string());
  EXPECT_EQ(sim.step_count(), 1500);
  sim.step();
  EXPECT_EQ(sim.step_count(), 1501);
}

// A file of format version 2 (before rotating and circle walls: no /walls/centre, radius, omega, angle) is still
// read: its walls do not rotate, and the run continues from it with the same bits as from the version 3 file.
TEST_F(CheckpointErrors, AVersionTwoFileWithoutWallRotationRestarts) {
  const fs::path file = copy("version-2.h5");
  {
    const H5 h(file);
    for (const char* set : {"/walls/centre", "/walls/radius", "/walls/omega", "/walls/angle"})
      ASSERT_GE(H5Ldelete(h.file, set, H5P_DEFAULT), 0) << set;
    h.set_int("/", "format_version", 2);
  }
  const Communicator self(MPI_COMM_SELF);
  QuietCout quiet;
  Simulation old_file(config_for(out("version-2")), self, true, file.string());
  Simulation new_file(config_for(out("version-3")), self, true, valid_->string());
  for (int k = 0; k < 20; ++k) old_file.step(), new_file.step();
  EXPECT_EQ(old_file.step_count(), 1520);
  EXPECT_EQ(test::first_difference(new_file.state_text(), old_file.state_text(), "version 3", "version 2"), "");
}

TEST_F(CheckpointErrors, MissingFiles) {
  // --resume of a directory without a checkpoint, and of one that does not exist.
  const fs::path empty = *dir_ / "empty";
  fs::create_directories(empty);
  std::ofstream(empty / "log.txt") << "a log, no checkpoint\n";
  EXPECT_TRUE(test::names(newest_refusal(empty), empty.string()));
  const fs::path nowhere = *dir_ / "no-such-dir";
  EXPECT_TRUE(test::names(newest_refusal(nowhere), nowhere.string()));
  // A restart file that does not exist.
  const fs::path missing = *dir_ / "no-such-checkpoint.h5";
  const std::string m = restart_refusal<InputError>(missing, out("missing"));
  EXPECT_TRUE(test::names(m, missing.string()));
  EXPECT_FALSE(fs::exists(out("missing"))) << "a refused restart created its output directory";
  // scene.type = file with a missing path.
  const std::string s = scene_file_refusal(missing, out("missing-scene"));
  EXPECT_TRUE(test::names(s, missing.string()));
  EXPECT_FALSE(fs::exists(out("missing-scene")));
}

TEST_F(CheckpointErrors, TruncatedFile) {
  const fs::path file = copy("truncated/checkpoint_0000001500.h5");
  fs::resize_file(file, fs::file_size(*valid_) / 2);
  const std::string m = restart_refusal<InputError>(file, out("truncated"));
  EXPECT_TRUE(test::names(m, file.string()));
  EXPECT_TRUE(test::names(m, "truncated"));
  EXPECT_FALSE(fs::exists(out("truncated")));
  EXPECT_TRUE(test::names(scene_file_refusal(file, out("truncated-scene")), file.string()));
  // --resume of a directory whose only checkpoint is truncated: the refusal names that file.
  const std::string r = newest_refusal(file.parent_path());
  EXPECT_TRUE(test::names(r, file.parent_path().string()));
  EXPECT_TRUE(test::names(r, file.filename().string()))
      << "--resume does not say which checkpoint it passed over, nor why";
}

TEST_F(CheckpointErrors, CorruptedSuperblock) {
  const fs::path file = copy("superblock.h5");
  overwrite_bytes(file, 0, 16, 'X');  // the HDF5 signature and the superblock versions
  const std::string m = restart_refusal<InputError>(file, out("superblock"));
  EXPECT_TRUE(test::names(m, file.string()));
  EXPECT_TRUE(test::names(m, "not an HDF5 file"));
  EXPECT_FALSE(fs::exists(out("superblock")));
  EXPECT_TRUE(test::names(scene_file_refusal(file, out("superblock-scene")), file.string()));
}

TEST_F(CheckpointErrors, CorruptedMiddleOfTheFile) {
  const fs::path file = copy("middle.h5");
  overwrite_bytes(file, fs::file_size(file) / 2, 32);
  const std::string m = restart_refusal<InputError>(file, out("middle"));
  EXPECT_TRUE(test::names(m, file.string()));
  EXPECT_FALSE(fs::exists(out("middle")));
}

TEST_F(CheckpointErrors, CorruptedDiscData) {
  // 32 bytes in the middle of the positions: raw data, no HDF5 metadata involved.
  const fs::path file = copy("positions.h5");
  haddr_t at = 0;
  hsize_t size = 0;
  {
    const H5 h(file);
    at = h.offset_of("/discs/position");
    size = h.storage_of("/discs/position");
  }
  ASSERT_NE(at, HADDR_UNDEF);
  ASSERT_GT(size, 64u);
  overwrite_bytes(file, at + size / 2, 32);
  const std::string m = restart_refusal<InputError>(file, out("positions"));
  EXPECT_TRUE(test::names(m, file.string()));
  EXPECT_FALSE(fs::exists(out("positions")));
}

TEST_F(CheckpointErrors, AnotherFormatVersion) {
  const std::int64_t next = kStateFormatVersion + 1;
  const fs::path file = copy("next-version.h5");
  H5(file).set_int("/", "format_version", next);
  const std::string m = restart_refusal<InputError>(file, out("next-version"));
  EXPECT_TRUE(test::names(m, file.string()));
  EXPECT_TRUE(test::names(m, "format version " + std::to_string(next)));
  EXPECT_TRUE(test::names(
      m, "versions " + std::to_string(kOldestReadableFormatVersion) + " to " + std::to_string(kStateFormatVersion)));
  EXPECT_FALSE(fs::exists(out("next-version")));
  EXPECT_TRUE(
      test::names(scene_file_refusal(file, out("next-version-scene")), "format version " + std::to_string(next)));

  // A file made by hand: the two identifying attributes only, version 99: refused on the version first.
  const fs::path hand = *dir_ / "by-hand.h5";
  {
    const hid_t f = H5Fcreate(hand.string().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(f);
    const H5 h(hand);
    h.set_string("/", "format", "rondel");
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a =
        H5Acreate_by_name(h.file, "/", "format_version", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const std::int64_t v = 99;
    H5Awrite(a, H5T_NATIVE_INT64, &v);
    H5Aclose(a);
    H5Sclose(space);
  }
  EXPECT_TRUE(test::names(restart_refusal<InputError>(hand, out("by-hand")), "format version 99"));

  // An HDF5 file of another program, and a text file.
  const fs::path foreign = *dir_ / "foreign.h5";
  H5Fclose(H5Fcreate(foreign.string().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  const std::string f = restart_refusal<InputError>(foreign, out("foreign"));
  EXPECT_TRUE(test::names(f, foreign.string()));
  EXPECT_TRUE(test::names(f, "not a Rondel checkpoint"));
  const fs::path text = *dir_ / "text.h5";
  std::ofstream(text) << "id,x,y,radius\n0,0.1,0.1,0.01\n";
  EXPECT_TRUE(test::names(restart_refusal<InputError>(text, out("text")), text.string()));
}

TEST_F(CheckpointErrors, IncompleteFile) {
  const fs::path file = copy("incomplete.h5");
  H5(file).remove("/", "complete");
  const std::string m = restart_refusal<InputError>(file, out("incomplete"));
  EXPECT_TRUE(test::names(m, file.string()));
  EXPECT_TRUE(test::names(m, "incomplete"));
}

TEST_F(CheckpointErrors, LawsOrHistorySlotsDiffer) {
  // Written with wang (xi, x_r); the configuration selects jiang_plastic (xi, theta_r).
  const std::string m = restart_refusal<InputError>(*valid_, out("laws"), "jiang_plastic");
  EXPECT_TRUE(test::names(m, valid_->string()));
  EXPECT_TRUE(test::names(m, "wang"));
  EXPECT_TRUE(test::names(m, "jiang_plastic"));
  EXPECT_TRUE(test::names(m, "run.reset_history"));
  EXPECT_FALSE(fs::exists(out("laws")));
  // The tangential law differs (no friction: the [coulomb] block goes).
  std::string frictionless = scene("wang");
  const std::string coulomb = "[coulomb]\nk_s = 7.5e6\nmu = 0.5\n";
  ASSERT_NE(frictionless.find(coulomb), std::string::npos);
  frictionless.replace(frictionless.find(coulomb), coulomb.size(), "");
  const std::string t = restart_refusal<InputError>(
      *valid_,
      parse_config_text(frictionless, {"--contact.tangential=none", "--run.output=" + out("tangential").string()}));
  EXPECT_TRUE(test::names(t, "tangential coulomb"));
  EXPECT_TRUE(test::names(t, "none"));
  // Same laws, but the file's history slots are not the kernel's.
  const fs::path slots = copy("slots.h5");
  H5(slots).set_string("/", "history_slots", "xi,x_r,extra");
  test::restamp(slots);
  const std::string s = restart_refusal<InputError>(slots, out("slots"));
  EXPECT_TRUE(test::names(s, slots.string()));
  EXPECT_TRUE(test::names(s, "xi,x_r,extra"));

  // Accepted with run.reset_history = true: discs, step and time from the file, no contact history.
  const Communicator self(MPI_COMM_SELF);
  QuietCout quiet;
  Simulation sim(config_for(out("reset"), "jiang_plastic", {"--run.reset_history=true"}), self, true, valid_->string());
  EXPECT_EQ(sim.step_count(), 1500);
  std::size_t with_history = 0;
  for (const ContactTable* t : {&sim.pairs(), &sim.wall_rows()})
    for (std::size_t r = 0; r < t->size(); ++r)
      for (const auto& column : t->slot) with_history += column[r] != 0.0;
  EXPECT_EQ(with_history, 0u) << "history carried over from a file of other laws";
  for (int s = 0; s < 10; ++s) sim.step();
  EXPECT_EQ(sim.step_count(), 1510);
}

TEST_F(CheckpointErrors, OutputDirectoryCannotBeWritten) {
  const fs::path blocker = *dir_ / "a-regular-file";
  std::ofstream(blocker) << "not a directory\n";
  const fs::path inside = blocker / "run";
  const Communicator self(MPI_COMM_SELF);
  for (const bool restart : {false, true}) {
    SCOPED_TRACE(restart ? "restart" : "new run");
    std::string m;
    try {
      QuietCout quiet;
      Simulation sim(config_for(inside), self, true, restart ? valid_->string() : "");
      ADD_FAILURE() << "run.output inside a regular file was accepted";
    } catch (const ConfigError& e) {
      m = e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "expected ConfigError, got " << typeid(e).name() << ": " << e.what();
    }
    EXPECT_TRUE(test::names(m, "run.output"));
    EXPECT_TRUE(test::names(m, inside.string()));
    EXPECT_TRUE(test::names(m, "cannot be written"));
  }
}

// A checkpoint killed half-way leaves the previous one usable, and --resume never picks it.
TEST_F(CheckpointErrors, InterruptedCheckpointIsNeverPicked) {
  const fs::path run = *dir_ / "interrupted";
  const Communicator self(MPI_COMM_SELF);
  {
    QuietCout quiet;
    Simulation sim(config_for(run, "wang", {"--run.overwrite=true", "--output.checkpoint_keep=5"}), self, true);
    for (int s = 0; s < 300; ++s) sim.step();
    sim.write_checkpoint();
    for (int s = 0; s < 300; ++s) sim.step();
    sim.write_checkpoint();
  }
  const fs::path first = run / Checkpointing::file_name("checkpoint", 300);
  const fs::path second = run / Checkpointing::file_name("checkpoint", 600);
  ASSERT_TRUE(fs::is_regular_file(first));
  ASSERT_TRUE(fs::is_regular_file(second));
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self), second.string());

  // A writer killed while writing step 900: its temporary file is left behind, half written.
  const fs::path part = run / ("." + Checkpointing::file_name("checkpoint", 900) + ".part");
  fs::copy_file(second, part);
  fs::resize_file(part, fs::file_size(second) / 2);
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self), second.string()) << "picked the .part file";
  // A complete-looking copy under the temporary name is not picked either (only checkpoint_<step>.h5 is).
  fs::copy_file(second, part, fs::copy_options::overwrite_existing);
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self), second.string()) << "picked the .part file";

  // The newest checkpoint truncated (a disk full, a copy cut short): the previous one is picked, and the
  // truncated one is reported as skipped with its reason.
  fs::resize_file(second, fs::file_size(second) / 2);
  std::vector<std::string> skipped;
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self, &skipped), first.string());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_TRUE(test::names(skipped[0], second.filename().string()));

  // A newest file without the final "complete" attribute (a writer stopped before its last write).
  const fs::path third = run / Checkpointing::file_name("checkpoint", 1200);
  fs::copy_file(first, third);
  H5(third).remove("/", "complete");
  skipped.clear();
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self, &skipped), first.string());
  ASSERT_EQ(skipped.size(), 2u);
  EXPECT_TRUE(test::names(skipped[0], "incomplete"));

  // The one picked restarts.
  QuietCout quiet;
  Simulation sim(config_for(*dir_ / "interrupted-resumed"), self, true, first.string());
  EXPECT_EQ(sim.step_count(), 300);
}

// Every attribute of every object (root, groups, datasets): (object path, attribute name).
std::vector<std::pair<std::string, std::string>> all_attributes(const fs::path& file) {
  std::vector<std::pair<std::string, std::string>> out;
  std::vector<std::string> objects{"/"};
  {
    Hdf5File f(file.string(), Hdf5File::Mode::read, Communicator(MPI_COMM_SELF));
    for (const auto& [path, dataset] : f.objects()) objects.push_back(path);
  }
  const H5 h(file);
  for (const std::string& o : objects) {
    const hid_t obj = H5Oopen(h.file, o.c_str(), H5P_DEFAULT);
    std::vector<std::string> names;
    H5Aiterate2(
        obj, H5_INDEX_NAME, H5_ITER_INC, nullptr,
        [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
          static_cast<std::vector<std::string>*>(data)->push_back(name);
          return 0;
        },
        &names);
    H5Oclose(obj);
    for (const std::string& n : names) out.emplace_back(o, n);
  }
  return out;
}

// Flips bit `bit` of the stored value of attribute `name` of `object` (its bytes as stored, no conversion).
void flip_attribute_bit(const fs::path& file, const std::string& object, const std::string& name, std::size_t bit) {
  const H5 h(file);
  // The object held open while its attribute is written (HDF5 1.10 cannot write one opened by path).
  const hid_t obj = H5Oopen(h.file, object.c_str(), H5P_DEFAULT);
  const hid_t a = H5Aopen(obj, name.c_str(), H5P_DEFAULT);
  const hid_t type = H5Aget_type(a);
  std::vector<unsigned char> bytes(H5Aget_storage_size(a));
  EXPECT_GE(H5Aread(a, type, bytes.data()), 0) << object << ":" << name;
  bytes[(bit / 8) % bytes.size()] ^= static_cast<unsigned char>(1u << (bit % 8));
  EXPECT_GE(H5Awrite(a, type, bytes.data()), 0) << object << ":" << name;
  H5Tclose(type);
  H5Aclose(a);
  H5Oclose(obj);
}

// A flipped bit in any attribute of the newest checkpoint (the header, the configuration, the ledger, the
// walls' reference lengths, the run metadata, a dataset's checksum, `complete` and the attributes' own
// checksum): --resume passes over it to the previous checkpoint, naming the file and why.
TEST_F(CheckpointErrors, AFlippedBitInAnyAttributeIsPassedOver) {
  const fs::path run = *dir_ / "flips";
  const Communicator self(MPI_COMM_SELF);
  {
    QuietCout quiet;
    Simulation sim(config_for(run, "wang", {"--run.overwrite=true"}), self, true);
    for (int s = 0; s < 200; ++s) sim.step();
    sim.write_checkpoint();
    for (int s = 0; s < 200; ++s) sim.step();
    sim.write_checkpoint();
  }
  const fs::path older = run / Checkpointing::file_name("checkpoint", 200);
  const fs::path newest = run / Checkpointing::file_name("checkpoint", 400);
  ASSERT_EQ(Checkpointing::newest_checkpoint(run.string(), self), newest.string());
  const auto attributes = all_attributes(newest);
  ASSERT_GT(attributes.size(), 50u) << "the walk found too few attributes";
  const fs::path pristine = *dir_ / "flips-pristine.h5";
  fs::copy_file(newest, pristine);
  std::size_t k = 0;
  for (const auto& [object, name] : attributes) {
    fs::copy_file(pristine, newest, fs::copy_options::overwrite_existing);
    flip_attribute_bit(newest, object, name, 8 * k + 3 * k % 8);  // a different byte and bit each time
    ++k;
    std::vector<std::string> skipped;
    EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self, &skipped), older.string())
        << "a flipped bit in " << object << ":" << name << " was not found";
    ASSERT_EQ(skipped.size(), 1u) << object << ":" << name;
    EXPECT_TRUE(test::names(skipped[0], newest.string())) << skipped[0];
  }
  // `complete` is checked by value.
  fs::copy_file(pristine, newest, fs::copy_options::overwrite_existing);
  H5(newest).set_int("/", "complete", 0);
  std::vector<std::string> skipped;
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self, &skipped), older.string());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_TRUE(test::names(skipped[0], "complete = 0"));
  // Untouched, it is taken again.
  fs::copy_file(pristine, newest, fs::copy_options::overwrite_existing);
  EXPECT_EQ(Checkpointing::newest_checkpoint(run.string(), self), newest.string());
}

// run.overwrite = true replaces an earlier run: its checkpoints must not be taken for the new run's.
TEST_F(CheckpointErrors, CheckpointsOfAnOverwrittenRunAreNeverPicked) {
  const fs::path run = *dir_ / "overwritten";
  const Communicator self(MPI_COMM_SELF);
  {
    QuietCout quiet;
    Simulation old_run(config_for(run, "wang", {"--run.overwrite=true"}), self, true);
    for (int s = 0; s < 600; ++s) old_run.step();
    old_run.write_checkpoint();
  }
  {
    QuietCout quiet;
    Simulation new_run(config_for(run, "jiang_plastic", {"--run.overwrite=true"}), self, true);
    for (int s = 0; s < 300; ++s) new_run.step();
    new_run.write_checkpoint();
  }
  const fs::path stale = run / Checkpointing::file_name("checkpoint", 600);
  EXPECT_FALSE(fs::exists(stale)) << "run.overwrite = true left the replaced run's " << stale.filename();
  std::string picked;
  try {
    picked = Checkpointing::newest_checkpoint(run.string(), self);
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
  }
  EXPECT_EQ(picked, (run / Checkpointing::file_name("checkpoint", 300)).string())
      << "--resume would continue the run that run.overwrite replaced (other laws, step 600)";
}

// The XDMF side-car lists every snapshot of the directory, those written before a restart included.
TEST_F(CheckpointErrors, SnapshotSeriesSurvivesAResume) {
  const fs::path run = *dir_ / "snapshots";
  const Communicator self(MPI_COMM_SELF);
  const std::vector<std::string> every{"--run.overwrite=true", "--output.snapshot_every=100",
                                       "--diagnostics.every=100"};
  {
    QuietCout quiet;
    auto more = every;
    more.push_back("--run.steps=400");
    Simulation first(config_for(run, "wang", more), self, true);
    first.run();
  }
  const fs::path checkpoint = run / Checkpointing::file_name("checkpoint", 400);
  ASSERT_TRUE(fs::is_regular_file(checkpoint));
  {
    QuietCout quiet;
    auto more = every;
    more.push_back("--run.steps=600");
    Simulation resumed(config_for(run, "wang", more), self, true, checkpoint.string());
    resumed.run();
  }
  const std::string xdmf = test::read_file(run / "snapshots.xdmf");
  for (int step = 100; step <= 600; step += 100) {
    const std::string name = Checkpointing::file_name("snapshot", step);
    EXPECT_TRUE(fs::is_regular_file(run / name)) << name;
    EXPECT_NE(xdmf.find(name + ":/discs/position"), std::string::npos)
        << "snapshots.xdmf does not list " << name << " (written before the restart at step 400)";
  }
}

}  // namespace
}  // namespace rondel
