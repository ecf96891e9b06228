// rondel: a 2D discrete element code for discs.
//   mpirun -n N rondel FILE.ini [--section.key=value ...]
//   mpirun -n N rondel [FILE.ini] --resume OUTPUT_DIR [--section.key=value ...]
//   rondel --version | --help
#include <mpi.h>

#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/HugePages.hpp"
#include "app/Launch.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/ExitCodes.hpp"
#include "core/StopSignal.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/Communicator.hpp"
#include "rondel/Version.hpp"

namespace {

bool version_requested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--version") == 0) return true;
  return false;
}

int run(int argc, char** argv, const rondel::Communicator& comm) {
  rondel::Launch s = rondel::prepare_launch({std::vector<std::string>(argv + 1, argv + argc)}, comm);
  if (s.nothing_to_do) {
    if (comm.root()) std::cout << rondel::nothing_to_do_message(s) << '\n';
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
  // Before MPI starts: may run the program again with huge pages for malloc (app/HugePages.hpp).
  const char* why = nullptr;
  if (!rondel::use_huge_pages(argv, why)) {
    std::cerr << "rondel: configuration error: " << why << '\n';
    return rondel::kExitInput.code;
  }
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
