"""The exceptions of the reader and the tools, and the exit codes they map to.

Exit codes shared by every tool in tools/ (docs/python.md):
    0  done
    1  bad input or usage: a file missing, unreadable or not what was expected, an option out of range;
       a one-line 'TOOL: error: MESSAGE' on stderr, never a traceback
    2  the input was read but a run or a check failed (a rondel run exited non-zero, a file is incomplete
       or of another format version, no heap to measure, ...)
"""

EXIT_OK = 0
EXIT_INPUT = 1
EXIT_FAILED = 2


class RondelError(Exception):
    """Base class of the errors the tools report as one line (exit code in .code)."""

    code = EXIT_INPUT


class RondelFileError(RondelError):
    """A file or directory that cannot be read as what was asked for; the message names it."""

    def __init__(self, path, why):
        self.path = str(path)
        self.why = why
        super().__init__(f"'{self.path}': {why}")


class UsageError(RondelError):
    """A bad option or combination of options (exit code 1)."""


class CheckFailed(RondelError):
    """The input was read but the analysis, a run or a check failed (exit code 2)."""

    code = EXIT_FAILED
