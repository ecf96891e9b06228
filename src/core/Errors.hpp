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

// What an error is, for the agreement of the ranks (parallel/Agreement.hpp) and the exit code (core/ExitCodes.hpp).
enum class ErrorKind : int { none = 0, config = 1, input = 2, instability = 3, io = 4, help = 5, internal = 6 };

}  // namespace rondel
