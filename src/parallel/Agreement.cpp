#include "parallel/Agreement.hpp"

#include <chrono>
#include <new>
#include <thread>
#include <vector>

#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "core/MemoryLimit.hpp"

namespace rondel {

namespace {

// The errors that settle() and raise_from() throw: the kind, catchable as before, and the mark.
template <class E>
struct Agreed final : E, AgreedMark {
  explicit Agreed(const std::string& message) : E(message) {}
};
template <>
struct Agreed<HelpRequested> final : HelpRequested, AgreedMark {
  explicit Agreed(const std::string& message) : HelpRequested{message} {}
};

// Throws the error of `kind` with `message`, wrapped in `As` (Agreed: with the mark; Plain: as it is).
template <template <class> class As>
[[noreturn]] void throw_kind(ErrorKind kind, const std::string& message) {
  switch (kind) {
    case ErrorKind::help:
      throw As<HelpRequested>(message);
    case ErrorKind::config:
      throw As<ConfigError>(message);
    case ErrorKind::input:
      throw As<InputError>(message);
    case ErrorKind::instability:
      throw As<InstabilityError>(message);
    case ErrorKind::io:
      throw As<IoError>(message);
    case ErrorKind::memory:
      throw As<MemoryError>(message);
    case ErrorKind::stopped:
      throw As<StoppedInSetup>(message);
    case ErrorKind::none:
    case ErrorKind::internal:
      break;
  }
  throw As<std::runtime_error>(message);
}

template <class E>
struct Plain final : E {
  explicit Plain(const std::string& message) : E(message) {}
};
template <>
struct Plain<HelpRequested> final : HelpRequested {
  explicit Plain(const std::string& message) : HelpRequested{message} {}
};

[[noreturn]] void throw_agreed(ErrorKind kind, const std::string& message) { throw_kind<Agreed>(kind, message); }

// Kind and message as bytes (the kind first), and back.
std::vector<char> encode(const std::exception_ptr& error) {
  std::string text(1, static_cast<char>(error_kind(error)));  // built up in steps: GCC 12 warns on an insert
  text += error_message(error);
  return std::vector<char>(text.begin(), text.end());
}

std::exception_ptr decode(const std::vector<char>& bytes) {
  if (bytes.empty()) return std::make_exception_ptr(std::runtime_error("an error was agreed without a message"));
  try {
    throw_agreed(static_cast<ErrorKind>(bytes[0]), std::string(bytes.begin() + 1, bytes.end()));
  } catch (...) {
    return std::current_exception();
  }
}

}  // namespace

std::string error_message(const std::exception_ptr& error) {
  if (!error) return "";
  try {
    std::rethrow_exception(error);
  } catch (const HelpRequested& h) {
    return h.text;
  } catch (const std::bad_alloc&) {
    return "an allocation failed (std::bad_alloc): the run needs more memory than " + memory_bound().source +
           " allows; the files written before stay complete (use more ranks or nodes, or a smaller scene)";
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
}

ErrorKind error_kind(const std::exception_ptr& error) {
  if (!error) return ErrorKind::none;
  try {
    std::rethrow_exception(error);
  } catch (const HelpRequested&) {
    return ErrorKind::help;
  } catch (const ConfigError&) {
    return ErrorKind::config;
  } catch (const InputError&) {
    return ErrorKind::input;
  } catch (const InstabilityError&) {
    return ErrorKind::instability;
  } catch (const IoError&) {
    return ErrorKind::io;
  } catch (const MemoryError&) {
    return ErrorKind::memory;
  } catch (const StoppedInSetup&) {
    return ErrorKind::stopped;
  } catch (const std::bad_alloc&) {
    return ErrorKind::memory;
  } catch (...) {
    return ErrorKind::internal;
  }
}

bool is_agreed(const std::exception_ptr& error) {
  if (!error) return false;
  try {
    std::rethrow_exception(error);
  } catch (const AgreedMark&) {
    return true;
  } catch (...) {
    return false;
  }
}

void throw_error(ErrorKind kind, const std::string& message) { throw_kind<Plain>(kind, message); }

void settle(const Communicator& comm, const std::exception_ptr& error) {
  int first = error ? comm.rank() : comm.size();
  if (comm.size() > 1) {
    comm.count_collective();
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm.comm());
  }
  if (first == comm.size()) return;
  raise_from(comm, first, error);
}

void raise_from(const Communicator& comm, int failed_rank, const std::exception_ptr& error) {
  std::vector<char> bytes;
  if (comm.rank() == failed_rank) bytes = encode(error);
  if (comm.size() > 1) comm.broadcast(bytes, failed_rank);
  std::rethrow_exception(decode(bytes));
}

bool settle_at_exit(MPI_Comm exit_comm, std::exception_ptr& error, double seconds) {
  int size = 1;
  MPI_Comm_size(exit_comm, &size);
  if (size == 1 || is_agreed(error)) return true;
  // A barrier that only failing ranks enter, polled against the deadline: a rank that never comes (stuck in
  // a collective of the run, or running on) must not keep this one waiting.
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibarrier(exit_comm, &request);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int done = 0;
  while (!done) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (std::chrono::steady_clock::now() > deadline) return false;  // the request dies with the job (abort)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  // Every rank failed: they take rank 0's error.
  std::vector<char> bytes;
  int rank = 0;
  MPI_Comm_rank(exit_comm, &rank);
  if (rank == 0) bytes = encode(error);
  long n = static_cast<long>(bytes.size());
  MPI_Bcast(&n, 1, MPI_LONG, 0, exit_comm);
  bytes.resize(static_cast<std::size_t>(n));
  MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_CHAR, 0, exit_comm);
  error = decode(bytes);
  return true;
}

}  // namespace rondel
