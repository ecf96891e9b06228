#pragma once
#include <exception>
#include <string>

#include "parallel/Communicator.hpp"

namespace rondel {

// Errors agreed among the ranks (docs/design.md section 6). A rank that fails keeps its exception instead of
// leaving the others waiting in the next collective; every rank then takes part in one agreement (a
// reduction of a flag). If any rank failed, every rank throws the error of the lowest failing rank, of the
// same kind (so the same exit code) and with the same message, and main prints it once, on rank 0.
//
//   agree(comm, [&] { work that may throw on some ranks only; });
//
// The kinds kept are ConfigError, InputError, InstabilityError, IoError and HelpRequested; anything else
// becomes an "internal error" (std::runtime_error) with its what().
enum class ErrorKind : int { none = 0, config = 1, input = 2, instability = 3, io = 4, help = 5, internal = 6 };

ErrorKind error_kind(const std::exception_ptr& error);
// Rebuilds an exception of `kind` with `message` and throws it.
[[noreturn]] void throw_error(ErrorKind kind, const std::string& message);

// Collective. Returns when no rank failed; otherwise every rank throws the lowest failing rank's error.
// `error` is this rank's (null when it did not fail).
void settle(const Communicator& comm, const std::exception_ptr& error);

// Collective: runs f on every rank and settles its outcome.
template <class F>
void agree(const Communicator& comm, F&& f) {
  std::exception_ptr error;
  try {
    f();
  } catch (...) {
    error = std::current_exception();
  }
  settle(comm, error);
}

// When a rank already knows (from a fused reduction, see Simulation::step) that `failed_rank` failed:
// that rank sends its error's kind and message to every rank, and every rank throws it. Collective.
[[noreturn]] void raise_from(const Communicator& comm, int failed_rank, const std::exception_ptr& error);

}  // namespace rondel
