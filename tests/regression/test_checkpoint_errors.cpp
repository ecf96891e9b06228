// Checkpoint and restart refusals (docs/design.md section 7, FORMAT.md): a missing, truncated, corrupted or
// foreign file, a file of another format version, a checkpoint whose laws or history slots differ from the
// configuration, and an output directory that cannot be written are refused by the Simulation constructor
// (so before any step runs and before any output file is written) with an InputError or ConfigError that
// names the file and says what is wrong. A checkpoint cut short (a leftover .part file, a truncated or
// incomplete newest file) is never picked by --resume: the previous complete one is. The signal path of the real
// executable is test_checkpoint_signal.cpp's; which checkpoint --resume takes, test_checkpoint_resume.cpp's.
//
// One rank (the regression binary, MPI initialised by its main).
#include "CheckpointFixture.hpp"

namespace rondel {
namespace {

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

}  // namespace
}  // namespace rondel
