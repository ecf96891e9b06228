// Files that lie, through the real executable on 1 to 3 ranks: an HDF5 checkpoint or scene file whose datasets
// and checksums are valid but whose discs are not (two discs with one id, a negative id, a radius that is not a
// number) is refused before any work, with one message naming the file, the dataset and the row or id, and the
// run directory it came from keeps every byte.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "support/Command.hpp"
#include "support/Restamp.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::mpirun_rondel;
using test::occurrences;
using test::Outcome;
using test::quoted;
using test::read_file;
using test::TempDir;

// Sets one value (component 0 of row `row`) of the dataset `name` of a closed Rondel file, and makes its
// checksum and the attributes' checksum fit: a file that another program wrote, not a damaged one.
template <class T>
void set_value(const fs::path& file, const char* name, std::size_t row, T value) {
  const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  {
    const hid_t f = H5Fopen(file.string().c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0) << file;
    const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    const hid_t space = H5Dget_space(d);
    hsize_t dims[2] = {0, 1};
    H5Sget_simple_extent_dims(space, dims, nullptr);
    const std::size_t width = H5Sget_simple_extent_ndims(space) == 2 ? dims[1] : 1;
    std::vector<T> values(dims[0] * width);
    H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    values.at(row * width) = value;
    H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    const std::uint64_t sum = Hdf5File::dataset_checksum(values.data(), width * sizeof(T), dims[0]);
    const hid_t a = H5Aopen(d, "checksum", H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_UINT64, &sum);
    H5Aclose(a);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
  }
  test::restamp(file);
}

// A run of the moving-wall box (130 discs) to step 20, checkpoints at 10 and 20, made once for the suite.
class LyingFiles : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("rondel-lying");
    test::write_file(*dir_ / "box.ini", test::moving_wall_box_ini("wang"));
    const Outcome o = mpirun_rondel(*dir_, 1, "box.ini --run.output=run --run.steps=20 --output.checkpoint_every=10");
    ASSERT_EQ(o.exit_code, 0) << o.err;
  }
  static void TearDownTestSuite() { delete dir_; }

  // A copy of the run in which the newest checkpoint (step 20) has been edited by `edit`.
  static fs::path edited_run(const std::string& name, const std::function<void(const fs::path&)>& edit) {
    const fs::path run = *dir_ / name;
    fs::remove_all(run);
    fs::copy(*dir_ / "run", run, fs::copy_options::recursive);
    edit(run / "checkpoint_0000000020.h5");
    return run;
  }
  // `--resume` of `run` on `ranks` ranks: refused with exit 1 and `message` printed once on stderr, and every
  // file of the run as it was.
  static void expect_resume_refused(const fs::path& run, int ranks, const std::string& message) {
    const auto before = test::read_tree(run);
    const Outcome o = mpirun_rondel(*dir_, ranks, "--resume " + quoted(run) + " --run.steps=40");
    EXPECT_EQ(o.exit_code, 1) << ranks << " ranks: " << o.err;
    EXPECT_EQ(occurrences(o.err, message), 1u) << ranks << " ranks: " << o.err;
    EXPECT_EQ(occurrences(o.err, "rondel: "), 1u) << o.err;
    EXPECT_TRUE(test::read_tree(run) == before) << ranks << " ranks: the run directory changed";
  }
  static TempDir* dir_;
};
TempDir* LyingFiles::dir_ = nullptr;

TEST_F(LyingFiles, TwoDiscsWithOneIdInACheckpointAreRefusedOnAnyRankCount) {
  const fs::path run = edited_run("twice", [](const fs::path& f) { set_value<std::int64_t>(f, "/discs/gid", 5, 3); });
  for (int ranks : {1, 2, 3})
    expect_resume_refused(run, ranks, "checkpoint_0000000020.h5': disc id 3 occurs more than once in /discs/gid");
}

TEST_F(LyingFiles, ANegativeOrTooLargeIdInACheckpointIsRefused) {
  const fs::path neg = edited_run("neg", [](const fs::path& f) { set_value<std::int64_t>(f, "/discs/gid", 1, -5); });
  for (int ranks : {1, 3})
    expect_resume_refused(neg, ranks,
                          "checkpoint_0000000020.h5': /discs/gid row 1 (disc -5) is -5: a disc id is an integer "
                          "from 0 to 2^53 - 1");
  const fs::path big = edited_run(
      "big", [](const fs::path& f) { set_value<std::int64_t>(f, "/discs/gid", 129, std::int64_t{1} << 53); });
  expect_resume_refused(big, 2, "/discs/gid row 129 (disc 9007199254740992) is 9007199254740992");
}

TEST_F(LyingFiles, ARadiusOrVelocityThatIsNotANumberIsRefusedNamingTheRow) {
  const fs::path nan = edited_run("nan", [](const fs::path& f) { set_value<double>(f, "/discs/radius", 7, NAN); });
  expect_resume_refused(nan, 2, "/discs/radius row 7 (disc 7) is nan: a radius is finite and > 0");
  const fs::path fast = edited_run("fast", [](const fs::path& f) { set_value<double>(f, "/discs/velocity", 64, 1e9); });
  expect_resume_refused(fast, 1, "/discs/velocity row 64 (disc 64) is (1e+09, ");
  const fs::path mass = edited_run("mass", [](const fs::path& f) { set_value<double>(f, "/discs/mass", 0, 0.0); });
  expect_resume_refused(mass, 3, "/discs/mass row 0 (disc 0) is 0: a mass is finite and > 0");
}

TEST_F(LyingFiles, AsAScene) {
  // The same file as scene.type = file: refused before the output directory exists.
  const fs::path run = edited_run("scene", [](const fs::path& f) { set_value<std::int64_t>(f, "/discs/gid", 9, 2); });
  for (int ranks : {1, 2}) {
    const Outcome o =
        mpirun_rondel(*dir_, ranks,
                      "box.ini --scene.type=file --scene.file=" + quoted(run / "checkpoint_0000000020.h5") +
                          " --run.output=out_scene --run.steps=5");
    EXPECT_EQ(o.exit_code, 1) << o.err;
    EXPECT_EQ(occurrences(o.err, "disc id 2 occurs more than once in /discs/gid"), 1u) << o.err;
    EXPECT_FALSE(fs::exists(*dir_ / "out_scene"));
  }
}

}  // namespace
}  // namespace rondel
