#include "parallel/Agreement.hpp"

#include <mpi.h>

#include <vector>

#include "core/Config.hpp"
#include "core/Errors.hpp"

namespace rondel {

namespace {

std::string message_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const HelpRequested& h) {
    return h.text;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown exception";
  }
}

}  // namespace

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
  } catch (...) {
    return ErrorKind::internal;
  }
}

void throw_error(ErrorKind kind, const std::string& message) {
  switch (kind) {
    case ErrorKind::help:
      throw HelpRequested{message};
    case ErrorKind::config:
      throw ConfigError(message);
    case ErrorKind::input:
      throw InputError(message);
    case ErrorKind::instability:
      throw InstabilityError(message);
    case ErrorKind::io:
      throw IoError(message);
    case ErrorKind::none:
    case ErrorKind::internal:
      break;
  }
  throw std::runtime_error(message);
}

void settle(const Communicator& comm, const std::exception_ptr& error) {
  int first = error ? comm.rank() : comm.size();
  if (comm.size() > 1) MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm.comm());
  if (first == comm.size()) return;
  raise_from(comm, first, error);
}

void raise_from(const Communicator& comm, int failed_rank, const std::exception_ptr& error) {
  std::vector<char> bytes;
  if (comm.rank() == failed_rank) {
    const std::string text = message_of(error);
    bytes.push_back(static_cast<char>(error_kind(error)));
    bytes.insert(bytes.end(), text.begin(), text.end());
  }
  if (comm.size() > 1) comm.broadcast(bytes, failed_rank);
  if (bytes.empty()) throw std::runtime_error("an error was agreed without a message");
  throw_error(static_cast<ErrorKind>(bytes[0]), std::string(bytes.begin() + 1, bytes.end()));
}

}  // namespace rondel
