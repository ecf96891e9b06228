#pragma once
#include <csignal>

namespace rondel {

// SIGTERM, SIGINT and SIGUSR1 ask the run to write a checkpoint and stop (a cluster's time limit, Ctrl-C,
// or a user's request). The handler only records the signal; the time loop polls it, and every rank agrees
// on the step (docs/design.md section 7). The flag is process-wide by nature (a signal handler cannot reach an
// object), the one global of the code.
//
// main installs the handlers before anything else, so that a signal during set-up (a SLURM job's SIGUSR1
// while it reads a large checkpoint) is recorded instead of killing the process: set-up then stops before the
// first file is written (Simulation, exit 10), or the first step's reduction takes it (a checkpoint, exit 10).
class StopSignal {
 public:
  // Installs the handlers (again: harmless); a signal already received stays received.
  static void install();
  // The signal received since the handlers were installed (0 when none).
  static int received();
  static const char* name(int signal);
};

}  // namespace rondel
