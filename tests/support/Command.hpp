#pragma once
// Test support: running the real executables from a test, as a shell command in a scratch directory.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/TempDir.hpp"

extern char** environ;

namespace rondel::test {

// What a command left behind: its exit code (-1 when it did not exit normally), stdout and stderr.
struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

// The build's rondel executable (beside the tests/ folder of the test binaries).
inline std::filesystem::path rondel_executable() {
  return std::filesystem::canonical("/proc/self/exe").parent_path().parent_path() / "rondel";
}

inline std::string quoted(const std::filesystem::path& p) {
  std::string s(1, '\'');  // built up in steps: GCC 12 warns (-Wrestrict, a false positive) on "'" + s + "'"
  s += p.string();
  s += '\'';
  return s;
}

// `env` arguments that remove Open MPI's launch environment (OMPI_*, PMIX_*, PMI_*), so that a command
// started from a test that itself runs under mpirun is a fresh singleton; with `keep_run_as_root` the
// OMPI_ALLOW_RUN_AS_ROOT* permissions stay.
inline std::string without_mpi_launch(bool keep_run_as_root) {
  std::string unset;
  for (char** e = environ; *e; ++e) {
    const std::string var(*e);
    const std::string name = var.substr(0, var.find('='));
    if (keep_run_as_root && name.rfind("OMPI_ALLOW_RUN_AS_ROOT", 0) == 0) continue;
    if (name.rfind("OMPI_", 0) == 0 || name.rfind("PMIX_", 0) == 0 || name.rfind("PMI_", 0) == 0)
      unset += " -u " + name;
  }
  return unset;
}

// Runs `env ENV COMMAND` through the shell in `dir`, stdout and stderr into stdout.txt and stderr.txt there,
// with no standard input.
inline Outcome run_in(const TempDir& dir, const std::string& env, const std::string& command) {
  const std::string cmd =
      "cd " + quoted(dir.path()) + " && env" + env + " " + command + " > stdout.txt 2> stderr.txt < /dev/null";
  const int status = std::system(cmd.c_str());
  Outcome o;
  if (status != -1 && WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  o.out = read_file(dir / "stdout.txt");
  o.err = read_file(dir / "stderr.txt");
  return o;
}

// Whether `program` is on the PATH.
inline bool have_program(const std::string& program) {
  return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0;
}

// `mpirun -n RANKS rondel ARGS` in `dir` under `timeout LIMIT` (a hang fails the caller's test instead of the
// CTest timeout), with a clean MPI environment (the caller may itself run under mpirun; the run-as-root
// permissions stay) plus `env` (" VAR=value ...").
inline Outcome mpirun_rondel(const TempDir& dir, int ranks, const std::string& args, const std::string& env = "",
                             int limit = 120) {
  std::string e = without_mpi_launch(true);
  if (geteuid() == 0) e += " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
  if (!env.empty()) e += " " + env;
  return run_in(dir, e,
                "timeout " + std::to_string(limit) + " mpirun -n " + std::to_string(ranks) + " --oversubscribe " +
                    quoted(rondel_executable()) + " " + args);
}

// How often `what` occurs in `text`.
inline std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace rondel::test
