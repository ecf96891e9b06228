#pragma once
#include <csignal>

namespace rondel {

// SIGTERM, SIGINT and SIGUSR1 ask the run to write a checkpoint and stop (a cluster's time limit, Ctrl-C,
// or a user's request). The handler only records the signal; the time loop polls it, and every rank agrees
// on the step (docs/design.md section 7). The flag is process-wide by nature (a signal handler cannot reach an
// object), the one global of the code.
class StopSignal {
 public:
  static void install();
  // The signal received since install() (0 when none).
  static int received();
  static const char* name(int signal);
};

}  // namespace rondel
