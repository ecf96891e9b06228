// I/O failures of the real executable on 1 to 3 ranks (README "Exit codes", docs/design.md section 7): a
// dataset write, a metadata flush or a space reservation that fails on one rank only (injected with
// RONDEL_FAULT, core/FaultInjection.hpp), a text output that cannot be written, a disk that is really full
// (a small tmpfs, where the machine lets the test mount one), a checkpoint whose dataset is one row short
// (only the last rank's block is out of range) and the leftovers of a killed checkpoint. Each stops every rank
// within seconds (each command runs under `timeout`) with the I/O exit code 5 or the input exit code 1 and
// the message printed once; the previous checkpoint stays, verified, and no partial file is left.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <semaphore.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/Checkpointing.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"
#include "support/Command.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::TempDir;

const fs::path kSource = RONDEL_SOURCE_DIR;
constexpr int kLimit = 120;  // seconds before `timeout` stops a command: a hang fails the test

Outcome rondel_on(const TempDir& dir, int ranks, const std::string& args, const std::string& env = "") {
  return test::mpirun_rondel(dir, ranks, args, env, kLimit);
}

std::size_t count(const std::string& text, const std::string& what) { return test::occurrences(text, what); }

// The deposition scene, small and short: a checkpoint every 50 steps, `steps` steps, into `run`.
std::string deposition(const fs::path& run, int steps = 150) {
  return test::quoted(kSource / "inputs/deposition.ini") + " --scene.count=600 --run.steps=" + std::to_string(steps) +
         " --output.checkpoint_every=50 --run.progress=false --run.overwrite=true --run.output=" + test::quoted(run);
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

bool has_part_file(const fs::path& dir) {
  for (const std::string& n : names_in(dir))
    if (n.find(".part") != std::string::npos) return true;
  return false;
}

// The newest checkpoint of `dir` that passes every check (as --resume picks it), "" when none does.
std::string newest_good(const fs::path& dir) {
  try {
    return Checkpointing::newest_checkpoint(dir.string(), Communicator(MPI_COMM_SELF));
  } catch (const std::exception&) {
    return "";
  }
}

// What every failed run must show: the exit code, the message once, no crash, no hang.
void expect_stopped(const Outcome& o, int code, const std::string& message, const std::string& tag) {
  EXPECT_EQ(o.exit_code, code) << tag << "; stderr:\n" << o.err;
  EXPECT_EQ(count(o.err, message), 1u) << tag << ": the message once; stderr:\n" << o.err;
  EXPECT_EQ(count(o.err, "error:"), 1u) << tag << ": one message only; stderr:\n" << o.err;
  EXPECT_EQ(o.err.find("Segmentation"), std::string::npos) << tag << ": crashed; stderr:\n" << o.err;
  EXPECT_EQ(o.err.find("signal"), std::string::npos) << tag << ": a signal; stderr:\n" << o.err;
}

// A checkpoint that fails on one rank only (the second checkpoint of the run, step 100): every rank stops
// with exit 5, the checkpoint of step 50 is kept and reads back, nothing partial is left, no final files.
TEST(IoFailures, AFailureOnOneRankOnlyStopsEveryRankAndKeepsThePreviousCheckpoint) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  struct Case {
    std::string site, message;
  };
  const std::vector<Case> cases = {
      {"hdf5_write", "cannot write dataset"},
      {"hdf5_close", "cannot write its metadata"},
      {"reserve", "not enough space to write"},
  };
  for (const Case& c : cases) {
    for (const int ranks : {2, 3}) {
      // hdf5_write and hdf5_close on the last rank; the reservation is rank 0's.
      const int rank = c.site == "reserve" ? 0 : ranks - 1;
      const std::string tag = c.site + "@" + std::to_string(rank) + ", " + std::to_string(ranks) + " ranks";
      TempDir dir("rondel-io-fail");
      const fs::path run = dir / "run";
      const Outcome o =
          rondel_on(dir, ranks, deposition(run), "RONDEL_FAULT=" + c.site + "@" + std::to_string(rank) + "#2");
      expect_stopped(o, 5, "rondel: I/O error:", tag);
      EXPECT_NE(o.err.find(c.message), std::string::npos) << tag << "; stderr:\n" << o.err;
      EXPECT_NE(o.err.find("checkpoint_0000000100.h5"), std::string::npos) << tag << ": names the file; " << o.err;
      EXPECT_EQ(newest_good(run), (run / "checkpoint_0000000050.h5").string()) << tag;
      EXPECT_FALSE(fs::exists(run / "checkpoint_0000000100.h5")) << tag;
      EXPECT_FALSE(has_part_file(run)) << tag;
      EXPECT_FALSE(fs::exists(run / "final.csv")) << tag;
      EXPECT_FALSE(fs::exists(run / "summary.json")) << tag;
      EXPECT_FALSE(fs::exists(run / "rondel.lock")) << tag << ": the lock was given back";
    }
  }
}

// A text output that cannot be written (an injected full disk at the file): exit 5 naming it, and the file
// is not left behind to be taken for a whole one.
TEST(IoFailures, TextOutputsThatCannotBeWrittenAreReported) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  for (const char* file : {"final.csv", "summary.txt", "summary.json", "config.ini"}) {
    for (const int ranks : {1, 3}) {
      const std::string tag = std::string(file) + ", " + std::to_string(ranks) + " rank(s)";
      TempDir dir("rondel-io-text");
      const fs::path run = dir / "run";
      const Outcome o = rondel_on(dir, ranks, deposition(run, 60), std::string("RONDEL_FAULT=text:") + file);
      expect_stopped(o, 5, "rondel: I/O error: cannot write '" + (run / file).string() + "'", tag);
      EXPECT_FALSE(fs::exists(run / file)) << tag;
      EXPECT_FALSE(fs::exists(run / "summary.json")) << tag << ": a failed run wrote summary.json";
      EXPECT_FALSE(fs::exists(run / "summary.txt")) << tag << ": a failed run wrote summary.txt";
    }
  }
}

// A real full disk: a tmpfs with room for the first checkpoint of the run but not for the second. Needs
// the right to mount (root in a container that allows it); skipped otherwise, the injected cases above
// stand in.
TEST(IoFailures, ASmallFileSystem) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  for (const int ranks : {1, 2, 3}) {
    const std::string tag = std::to_string(ranks) + " rank(s)";
    TempDir dir("rondel-io-small");
    // The size of one checkpoint of this scene, from a run on a normal disk.
    const fs::path probe = dir / "probe";
    const Outcome p = rondel_on(dir, 1, deposition(probe, 50) + " --output.checkpoint_at_end=false");
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const auto one = fs::file_size(probe / "checkpoint_0000000050.h5");
    const fs::path mnt = dir / "small";
    fs::create_directories(mnt);
    const std::string size = "size=" + std::to_string((one * 3 / 2 + 4095) / 4096 * 4096 + 64 * 1024);
    if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, size.c_str()) != 0)
      GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << ")";
    const fs::path run = mnt / "run";
    const Outcome o = rondel_on(dir, ranks, deposition(run));
    expect_stopped(o, 5, "rondel: I/O error:", tag);
    EXPECT_NE(o.err.find("No space left on device"), std::string::npos) << tag << "; stderr:\n" << o.err;
    EXPECT_EQ(newest_good(run), (run / "checkpoint_0000000050.h5").string()) << tag;
    EXPECT_FALSE(has_part_file(run)) << tag;
    EXPECT_FALSE(fs::exists(run / "summary.json")) << tag;
    ::umount2(mnt.c_str(), MNT_DETACH);
  }
}

// Rewrites `dataset` of `file` with its last row left out (without its checksum), with the HDF5 C API on
// this process.
void drop_last_row(const fs::path& file, const char* dataset) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, dataset, H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
  const hid_t type = H5Dget_type(d);
  const std::size_t row = H5Tget_size(type) * (rank == 2 ? dims[1] : 1);
  std::vector<char> data(dims[0] * row);
  H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Ldelete(f, dataset, H5P_DEFAULT);
  dims[0] -= 1;
  const hid_t shorter = H5Screate_simple(rank, dims, nullptr);
  const hid_t n = H5Dcreate2(f, dataset, type, shorter, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(n, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  H5Dclose(n);
  H5Sclose(shorter);
  H5Tclose(type);
  H5Fclose(f);
  // The attributes' checksum made to fit (as a writer with a bug would have stamped it), so that what is
  // found is the row count.
  std::uint64_t digest = 0;
  {
    const Hdf5File check(file.string(), Hdf5File::Mode::read, Communicator(MPI_COMM_SELF));
    digest = check.attribute_digest();
  }
  const hid_t g = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  const hid_t o = H5Oopen(g, "/integrity", H5P_DEFAULT);  // held open: HDF5 1.10 writes no attribute by path
  const hid_t a = H5Aopen(o, "attributes_checksum", H5P_DEFAULT);
  const auto stored = static_cast<std::int64_t>(digest);  // the bits, as the writer stores them
  H5Awrite(a, H5T_NATIVE_INT64, &stored);
  H5Aclose(a);
  H5Oclose(o);
  H5Fclose(g);
}

// A checkpoint whose /discs/radius is one row short: only the last rank's block lies outside it. --resume
// passes over it to the previous one with the reason; with no other checkpoint every rank stops with exit
// 1; read directly as a scene file it stops every rank with exit 1 naming the file.
TEST(IoFailures, ADatasetOneRowShortIsPassedOverOrRefusedOnEveryRank) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  for (const int ranks : {2, 3}) {
    const std::string tag = std::to_string(ranks) + " ranks";
    TempDir dir("rondel-io-short");
    const fs::path run = dir / "run";
    ASSERT_EQ(rondel_on(dir, ranks, deposition(run, 100)).exit_code, 0) << tag;
    const fs::path newest = run / "checkpoint_0000000100.h5";
    drop_last_row(newest, "/discs/radius");
    fs::copy_file(newest, dir / "short.h5");
    Outcome o = rondel_on(dir, ranks, "--resume " + test::quoted(run) + " --run.steps=150");
    EXPECT_EQ(o.exit_code, 0) << tag << "; stderr:\n" << o.err;
    EXPECT_NE(o.err.find("skipping " + newest.string()), std::string::npos) << tag << "; stderr:\n" << o.err;
    EXPECT_NE(o.err.find("/discs/radius has 599 rows"), std::string::npos) << tag << "; stderr:\n" << o.err;
    EXPECT_NE(o.out.find("resumed at step 50"), std::string::npos) << tag << "; stdout:\n" << o.out;

    const fs::path alone = dir / "alone";
    fs::create_directories(alone);
    fs::copy_file(dir / "short.h5", alone / "checkpoint_0000000100.h5");
    o = rondel_on(dir, ranks, "--resume " + test::quoted(alone));
    expect_stopped(o, 1, "no complete checkpoint", tag + ", resume");

    o = rondel_on(
        dir, ranks,
        deposition(dir / "from-file", 10) + " --scene.type=file --scene.file=" + test::quoted(dir / "short.h5"));
    expect_stopped(o, 1, "rondel: input error:", tag + ", scene file");
    EXPECT_NE(o.err.find("short.h5"), std::string::npos) << tag << "; stderr:\n" << o.err;
  }
}

// What a checkpoint killed inside MPI_File_open leaves (its .part file, an OMPIO semaphore in /dev/shm named
// after it, and one named after the next attempt's old-style name) blocks no later checkpoint, with Open
// MPI's OMPIO chosen explicitly too.
TEST(IoFailures, LeftoversOfAKilledCheckpointBlockNothing) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  TempDir dir("rondel-io-stale");
  const fs::path run = dir / "run";
  ASSERT_EQ(rondel_on(dir, 2, deposition(run, 50)).exit_code, 0);
  std::vector<std::string> semaphores;
  for (const std::string part : {".checkpoint_0000000100.h5.part", ".checkpoint_0000000100.h5.1-0.part"}) {
    test::write_file(run / part, "half a checkpoint");
    const std::string name = "/OMPIO_" + part;
    sem_t* s = sem_open(name.c_str(), O_CREAT, 0644, 0);  // taken: a waiter would wait for good
    if (s != SEM_FAILED) sem_close(s), semaphores.push_back(name);
  }
  for (const char* io : {"", "OMPI_MCA_io=ompio"}) {
    const Outcome o = rondel_on(dir, 2, "--resume " + test::quoted(run) + " --run.steps=" + (*io ? "150" : "100"), io);
    EXPECT_EQ(o.exit_code, 0) << io << "; stderr:\n" << o.err;
    EXPECT_FALSE(has_part_file(run)) << io;
  }
  EXPECT_EQ(newest_good(run), (run / "checkpoint_0000000150.h5").string());
  for (const std::string& s : semaphores) sem_unlink(s.c_str());
}

}  // namespace
}  // namespace rondel
