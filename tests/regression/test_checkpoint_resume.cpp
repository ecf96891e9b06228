// Which checkpoint --resume takes (docs/design.md section 7, FORMAT.md): a checkpoint killed half-way, one with a
// flipped bit in any attribute and one of a run that run.overwrite replaced are passed over for the previous
// complete one of this run; the XDMF series of the snapshots survives a resume. Split from
// test_checkpoint_errors.cpp (the refusals), with which it shares CheckpointFixture.hpp.
//
// One rank (the regression binary, MPI initialised by its main).
#include "CheckpointFixture.hpp"

namespace rondel {
namespace {

// The same fixture, a suite of its own (its own valid checkpoint).
class CheckpointResume : public CheckpointErrors {};

// A checkpoint killed half-way leaves the previous one usable, and --resume never picks it.
TEST_F(CheckpointResume, InterruptedCheckpointIsNeverPicked) {
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
TEST_F(CheckpointResume, AFlippedBitInAnyAttributeIsPassedOver) {
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
TEST_F(CheckpointResume, CheckpointsOfAnOverwrittenRunAreNeverPicked) {
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
TEST_F(CheckpointResume, SnapshotSeriesSurvivesAResume) {
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
