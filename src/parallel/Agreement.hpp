#pragma once
#include <mpi.h>

#include <exception>
#include <string>

#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// Errors agreed among the ranks (docs/design.md section 6). A rank that fails keeps its exception instead of
// leaving the others waiting in the next collective; every rank then takes part in one agreement (a
// reduction of a flag). If any rank failed, every rank throws the error of the lowest failing rank, of the
// same kind (so the same exit code) and with the same message, and main prints it once, on rank 0.
//
//   agree(comm, [&] { work that may throw on some ranks only; });
//
// The work inside agree() should call no collective, or only collectives that every rank reaches whatever
// happens (a nested agree is fine: its agreement is the same reduction as the outer one's). The kinds kept
// are ConfigError, InputError, InstabilityError, IoError and HelpRequested; anything else becomes an
// "internal error" (std::runtime_error) with its what().

// Carried by every error that settle() or raise_from() throws: every rank throws it together, so an agree
// around it rethrows it as it is (no second agreement) and main knows that it need not wait for the others.
struct AgreedMark {};

ErrorKind error_kind(const std::exception_ptr& error);
// The message of an error (HelpRequested: its text).
std::string error_message(const std::exception_ptr& error);
// True when every rank threw this error together (it carries AgreedMark).
bool is_agreed(const std::exception_ptr& error);
// Rebuilds an exception of `kind` with `message` and throws it (without the mark: this rank's own error).
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
  } catch (const AgreedMark&) {
    throw;  // an inner agreement: every rank has thrown it already
  } catch (...) {
    error = std::current_exception();
  }
  settle(comm, error);
}

// When a rank already knows (from a fused reduction, see Simulation::step) that `failed_rank` failed:
// that rank sends its error's kind and message to every rank, and every rank throws it. Collective.
[[noreturn]] void raise_from(const Communicator& comm, int failed_rank, const std::exception_ptr& error);

// main's last resort, for an error that reached it without the mark (thrown outside any agree, on every rank
// alike or on some only). The failing ranks meet on `exit_comm`, a duplicate of the world communicator used
// for nothing else (so that a rank still waiting in a collective of the run cannot be matched by mistake).
// If every rank arrives within `seconds`, `error` becomes rank 0's error, with the mark, on every rank, and
// the result is true; otherwise the result is false (some rank is stuck or still working) and the caller
// aborts the job. Collective over the ranks that fail; returns at once on one rank.
bool settle_at_exit(MPI_Comm exit_comm, std::exception_ptr& error, double seconds);

}  // namespace rondel
