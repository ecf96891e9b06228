// The signal path of the real executable (docs/design.md section 7): SIGTERM -> a checkpoint, exit 10, summary
// "stopped"; --resume runs to the end (exit 0) and ends in the bits of an uninterrupted run.
//
// One rank (the regression binary, MPI initialised by its main); the executable is started as a singleton.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "app/Checkpointing.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "support/Assertions.hpp"
#include "support/TempDir.hpp"

extern char** environ;

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

fs::path rondel_binary() { return fs::canonical("/proc/self/exe").parent_path().parent_path() / "rondel"; }

// Starts `rondel ARGS` in `dir` with a clean MPI environment (a singleton even under mpirun), stdout and
// stderr to dir/<tag>.out and dir/<tag>.err. Everything is prepared before fork: the child only calls
// async-signal-safe functions.
pid_t spawn_rondel(const fs::path& dir, const std::vector<std::string>& args, const std::string& tag) {
  static std::vector<std::string> env_store, arg_store;
  env_store.clear();
  for (char** e = environ; *e; ++e) {
    const std::string var(*e);
    const std::string name = var.substr(0, var.find('='));
    if (name.rfind("OMPI_", 0) == 0 || name.rfind("PMIX_", 0) == 0 || name.rfind("PMI_", 0) == 0) continue;
    env_store.push_back(var);
  }
  arg_store = {rondel_binary().string()};
  arg_store.insert(arg_store.end(), args.begin(), args.end());
  std::vector<char*> envp, argv;
  for (auto& s : env_store) envp.push_back(s.data());
  envp.push_back(nullptr);
  for (auto& s : arg_store) argv.push_back(s.data());
  argv.push_back(nullptr);
  const std::string out = (dir / (tag + ".out")).string(), err = (dir / (tag + ".err")).string();
  const std::string cwd = dir.string();
  const pid_t pid = fork();
  if (pid == 0) {
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int in = open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || in < 0 || chdir(cwd.c_str()) != 0) _exit(127);
    dup2(in, 0);
    dup2(o, 1);
    dup2(e, 2);
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  return pid;
}

// Waits for the child; its exit code, 128 + signal when killed, -1 on a timeout (then it is killed).
int wait_for(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (r < 0) return -2;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

std::size_t line_count(const fs::path& p) {
  std::ifstream in(p);
  std::size_t n = 0;
  for (std::string l; std::getline(in, l);) ++n;
  return n;
}

std::vector<fs::path> checkpoints_in(const fs::path& dir) {
  std::vector<fs::path> out;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string n = e.path().filename().string();
      if (n.rfind("checkpoint_", 0) == 0 && e.path().extension() == ".h5") out.push_back(e.path());
    }
  std::sort(out.begin(), out.end());
  return out;
}

// 1000 discs resting on the floor of a box: about 4 s of work on one core, so the run is still going when
// the signal comes.
const char* kLongRun = R"(
[run]
steps = 90000
progress = false
[diagnostics]
every = 500
[domain]
xlo = 0
xhi = 0.08
ylo = 0
yhi = 0.06
[gravity]
y = -9.81
[linear]
k_n = 1e6
e = 0.5
[coulomb]
k_s = 7.5e5
mu = 0.5
[contact]
rolling = wang
[wang]
k_r = 2e5
mu_r = 0.1
[walls]
box = bottom left right
[scene]
type = lattice_square
nx = 40
ny = 25
radius = 0.00099
spacing = 0.002
x0 = 0.001
y0 = 0.001
omega = 5
)";

TEST(CheckpointSignal, SigtermWritesACheckpointAndResumeFinishesTheRun) {
  ASSERT_TRUE(fs::exists(rondel_binary())) << rondel_binary();
  TempDir dir;
  const fs::path out = dir / "run";
  std::ofstream(dir / "long.ini") << kLongRun;

  const pid_t pid = spawn_rondel(dir.path(), {"long.ini", "--run.output=" + out.string()}, "first");
  ASSERT_GT(pid, 0);
  // Wait until the time loop runs (diagnostics rows past step 0: the signal handlers are installed), then
  // a little longer, and send SIGTERM.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (line_count(out / "diagnostics.csv") < 3 && std::chrono::steady_clock::now() < give_up &&
         waitpid(pid, nullptr, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  ASSERT_EQ(kill(pid, SIGTERM), 0) << "the run ended before the signal (make kLongRun longer)";
  const int code = wait_for(pid, 120);
  const std::string err = test::read_file(dir / "first.err");
  ASSERT_EQ(code, 10) << "stderr: " << err;
  const auto written = checkpoints_in(out);
  ASSERT_EQ(written.size(), 1u) << "one checkpoint, at the step of the signal";
  const StateHeader h = read_state_header(written[0].string(), Communicator(MPI_COMM_SELF));
  EXPECT_GT(h.step, 0);
  EXPECT_LT(h.step, 90000) << "the run was not stopped early";
  const std::string summary = test::read_file(out / "summary.txt");
  EXPECT_TRUE(test::names(summary, "stopped by a signal"));
  EXPECT_TRUE(test::names(summary, "--resume " + out.string()));
  EXPECT_TRUE(test::names(test::read_file(out / "log.txt"), "stopped by SIGTERM at step " + std::to_string(h.step)));
  std::cout << "[ signal   ] SIGTERM stopped the run at step " << h.step << " of 90000\n";

  // --resume without the INI: the checkpoint's configuration; the run goes on to run.steps = 90000.
  const pid_t again = spawn_rondel(dir.path(), {"--resume", out.string()}, "resume");
  ASSERT_GT(again, 0);
  const int code2 = wait_for(again, 180);
  ASSERT_EQ(code2, 0) << "stderr: " << test::read_file(dir / "resume.err");
  EXPECT_TRUE(test::names(test::read_file(out / "summary.txt"), "status: complete"));
  EXPECT_TRUE(test::names(test::read_file(out / "log.txt"), "resumed at step " + std::to_string(h.step)));
  const auto after = checkpoints_in(out);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(after.back().filename().string(), Checkpointing::file_name("checkpoint", 90000));
  const std::string resumed_final = test::read_file(out / "final.csv");

  // The same run without interruption ends in the same bits.
  const fs::path straight = dir / "straight";
  const pid_t ref = spawn_rondel(dir.path(), {"long.ini", "--run.output=" + straight.string()}, "straight");
  ASSERT_EQ(wait_for(ref, 180), 0) << test::read_file(dir / "straight.err");
  const std::string straight_final = test::read_file(straight / "final.csv");
  EXPECT_GT(std::count(straight_final.begin(), straight_final.end(), '\n'), 1000);
  EXPECT_TRUE(resumed_final == straight_final)
      << "final.csv after SIGTERM + --resume differs from the uninterrupted run";
}

}  // namespace
}  // namespace rondel
