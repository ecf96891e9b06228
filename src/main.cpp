// rondel: a 2D discrete element code for discs.
//   mpirun -n N rondel FILE.ini [--section.key=value ...]
//   mpirun -n N rondel [FILE.ini] --resume OUTPUT_DIR [--section.key=value ...]
//   rondel --version | --help
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/Checkpointing.hpp"
#include "app/OutputNames.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/ExitCodes.hpp"
#include "core/FaultInjection.hpp"
#include "core/StopSignal.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "rondel/Version.hpp"

namespace {

// The --resume directory, if any, and whether an INI file was named.
std::string resume_directory(int argc, char** argv, bool& has_file) {
  std::string dir;
  has_file = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--resume" && i + 1 < argc)  // read before the configuration, which it may come from
      dir = argv[++i];
    else if (a.rfind("--resume=", 0) == 0)
      dir = a.substr(9);
    else if (a.rfind("--", 0) != 0)
      has_file = true;
  }
  return dir;
}

bool version_requested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--version") == 0) return true;
  return false;
}

// A resumed run has work to do only below run.steps: at it there is nothing to do (true: say so and stop),
// above it the configuration is wrong.
bool nothing_to_resume(const rondel::Config& config, const std::string& checkpoint, std::int64_t step) {
  if (config.steps > step) return false;
  if (config.steps < step)
    throw rondel::ConfigError("run.steps = " + std::to_string(config.steps) + " is below the step " +
                              std::to_string(step) + " of the checkpoint '" + checkpoint +
                              "' to resume from; run.steps counts from the start of the run: set run.steps > " +
                              std::to_string(step) + " to continue it");
  return true;
}

// The set-up before the Simulation: the checkpoint to resume from and the configuration, each step agreed
// among the ranks (an error on one rank, a file it cannot read, stops every rank before the next collective).
struct Setup {
  rondel::Config config;
  std::string checkpoint;
  bool nothing_to_do = false;
};

Setup set_up(int argc, char** argv, const rondel::Communicator& comm) {
  Setup s;
  bool has_file = false;
  const std::string resume = resume_directory(argc, argv, has_file);
  rondel::StateHeader header;
  if (!resume.empty()) {
    std::vector<std::string> skipped;
    rondel::agree(comm, [&] { s.checkpoint = rondel::Checkpointing::newest_checkpoint(resume, comm, &skipped); });
    if (comm.root())
      for (const auto& k : skipped) std::cerr << "rondel: skipping " << k << '\n';
    rondel::agree(comm, [&] { header = rondel::read_state_header(s.checkpoint, comm); });
  }
  // A fault-injection hook that injects nothing is refused before any work (core/FaultInjection.hpp).
  rondel::agree(comm, [] { rondel::check_fault_injection(rondel::output::kTextFiles); });
  rondel::agree(comm, [&] {
    if (!resume.empty() && !has_file) {
      // No INI: the configuration stored in the checkpoint, with the command line's overrides.
      // It continues in DIR itself, unless the command line names another run.output.
      std::vector<std::string> args(argv + 1, argv + argc);
      const bool named =
          std::any_of(args.begin(), args.end(), [](const std::string& a) { return a.rfind("--run.output", 0) == 0; });
      if (!named) args.push_back("--run.output=" + resume);
      s.config = rondel::parse_config_text(header.config, args);
    } else {
      s.config = rondel::parse_config(argc, argv);
    }
    s.nothing_to_do = !resume.empty() && nothing_to_resume(s.config, s.checkpoint, header.step);
  });
  return s;
}

int run(int argc, char** argv, const rondel::Communicator& comm) {
  Setup s = set_up(argc, argv, comm);
  if (s.nothing_to_do) {
    if (comm.root())
      std::cout << "rondel: nothing to do: the checkpoint '" << s.checkpoint << "' is at step " << s.config.steps
                << " = run.steps already (the run is complete); raise run.steps (--run.steps=N) to continue it\n";
    return rondel::kExitDone.code;
  }
  rondel::Simulation sim(std::move(s.config), comm, true, s.checkpoint);
  const rondel::RunSummary summary = sim.run();
  return summary.stop_signal != 0 ? rondel::kExitStopped.code : rondel::kExitDone.code;
}

// How long the failing ranks wait for each other at the end (settle_at_exit) before one aborts the job.
constexpr double kExitAgreementSeconds = 10.0;

// The error that ended the run on this rank. Agreed (every rank has it): rank 0 prints it once and every rank
// returns its code. Otherwise the failing ranks try to meet; if some rank does not come (it waits in a
// collective, or runs on), this rank prints its own error and aborts the whole job with the code, never a hang.
int report(std::exception_ptr error, MPI_Comm exit_comm, const rondel::Communicator& comm) {
  const bool agreed = rondel::settle_at_exit(exit_comm, error, kExitAgreementSeconds);
  const rondel::ErrorKind kind = rondel::error_kind(error);
  const rondel::ErrorExit& exit = rondel::error_exit(kind);
  const std::string message = rondel::error_message(error);
  if (agreed && kind == rondel::ErrorKind::help) {
    if (comm.root()) std::cout << message;
    return exit.exit.code;
  }
  if (agreed) {
    if (comm.root()) std::cerr << "rondel: " << exit.label << message << '\n';
    return exit.exit.code;
  }
  std::cerr << "rondel: " << exit.label << message << " (found on rank " << comm.rank()
            << " only; stopping every rank)\n"
            << std::flush;
  MPI_Abort(MPI_COMM_WORLD, exit.exit.code);
  return exit.exit.code;
}

}  // namespace

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  // Before anything is read or written: a stop signal during set-up is recorded, not fatal (core/StopSignal.hpp).
  rondel::StopSignal::install();
  rondel::Communicator comm;
  // Exit codes: core/ExitCodes.hpp (README "Exit codes"). Every rank returns the same code; the message is printed
  // once.
  if (version_requested(argc, argv)) {
    if (comm.root()) std::cout << "rondel " << rondel::kRondelVersion << " (commit " << rondel::kRondelCommit << ")\n";
    return rondel::kExitDone.code;
  }
  // Only for the agreement at the end (report): a communicator of its own, so it cannot meet a collective
  // that another rank is still waiting in.
  MPI_Comm exit_comm = MPI_COMM_NULL;
  MPI_Comm_dup(MPI_COMM_WORLD, &exit_comm);
  int code = 0;
  try {
    code = run(argc, argv, comm);
  } catch (...) {
    code = report(std::current_exception(), exit_comm, comm);
  }
  MPI_Comm_free(&exit_comm);
  return code;
}
