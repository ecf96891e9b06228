#pragma once
#include <stdexcept>
#include <string>

namespace rondel {

// A user's mistake in the configuration (a key, a value): main reports it once and exits non-zero.
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A problem with an input file or with the scene it describes.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The run became unphysical (an overlap or an energy that blew up).
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Reading or writing a file failed (disk full, permissions, a damaged file system): main exits with its
// own code, the partial file is removed and the previous checkpoint is kept.
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An allocation failed (std::bad_alloc) after the checks before work: the run needs more memory than this
// process may have. Its own exit code; the files written before it stay complete.
struct MemoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A stop signal arrived during set-up, before the output directory was written (core/StopSignal.hpp): every rank
// ends with the exit code of a stopped run (10); a rerun of the same command (or --resume) starts again.
struct StoppedInSetup : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// What an error is, for the agreement of the ranks (parallel/Agreement.hpp) and the exit code (core/ExitCodes.hpp).
enum class ErrorKind : int {
  none = 0,
  config = 1,
  input = 2,
  instability = 3,
  io = 4,
  help = 5,
  internal = 6,
  memory = 7,
  stopped = 8
};

}  // namespace rondel
