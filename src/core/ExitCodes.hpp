#pragma once
// The exit codes of rondel, one row each, and the code and message label of each kind of error. main returns
// them; the README's table "Exit codes" lists exactly these rows (tests/regression/test_exit_codes.cpp checks
// it), and the SLURM job scripts (tools/cluster) resubmit on kExitStopped.
#include "core/Errors.hpp"

namespace rondel {

struct ExitCode {
  int code;
  const char* meaning;
};

inline constexpr ExitCode kExitDone{0, "done; also --help, --version, and a --resume with nothing to do"};
inline constexpr ExitCode kExitInput{1, "configuration or input error, before any work"};
inline constexpr ExitCode kExitUnstable{3, "the run became unstable"};
inline constexpr ExitCode kExitInternal{4, "internal error"};
inline constexpr ExitCode kExitIo{5, "I/O error: a file could not be written or read"};
inline constexpr ExitCode kExitMemory{6,
                                      "out of memory: an allocation failed (the files written before stay complete)"};
inline constexpr ExitCode kExitStopped{
    10, "stopped by SIGTERM, SIGINT or SIGUSR1 after writing a checkpoint, or during set-up before writing anything"};
inline constexpr ExitCode kExitCodes[] = {kExitDone, kExitInput,  kExitUnstable, kExitInternal,
                                          kExitIo,   kExitMemory, kExitStopped};

// The exit code of an error of each kind, and the label of its message ("rondel: configuration error: ...").
struct ErrorExit {
  ErrorKind kind;
  const ExitCode& exit;
  const char* label;
};
inline constexpr ErrorExit kErrorExits[] = {
    {ErrorKind::none, kExitDone, ""},
    {ErrorKind::help, kExitDone, ""},
    {ErrorKind::config, kExitInput, "configuration error: "},
    {ErrorKind::input, kExitInput, "input error: "},
    {ErrorKind::instability, kExitUnstable, "the run became unstable: "},
    {ErrorKind::io, kExitIo, "I/O error: "},
    {ErrorKind::internal, kExitInternal, "internal error: "},
    {ErrorKind::memory, kExitMemory, "out of memory: "},
    {ErrorKind::stopped, kExitStopped, ""},
};
inline const ErrorExit& error_exit(ErrorKind kind) {
  for (const ErrorExit& e : kErrorExits)
    if (e.kind == kind) return e;
  return kErrorExits[6];  // internal
}

}  // namespace rondel
