#pragma once
// What a reader may open: a regular file (symbolic links followed) of a bounded size. A character device
// (/dev/zero, /dev/urandom), a FIFO or a socket would be read forever, block or grow memory without bound;
// they are refused before anything is read, naming the file and what it is.
#include <cstdint>
#include <limits>
#include <string>

namespace rondel {

// An INI file larger than this is not a configuration (the largest shipped one is a few kB).
inline constexpr std::uint64_t kMaxIniBytes = std::uint64_t{16} << 20;

// Why `path` cannot be read as an input file ("" when it can): it is missing, a directory, a device, a FIFO,
// a socket, or larger than `max_bytes` (the message names the size and the bound). `what` names the file's
// role ("the configuration file", "scene.file").
std::string input_file_problem(const std::string& path, const std::string& what,
                               std::uint64_t max_bytes = std::numeric_limits<std::uint64_t>::max());

// What the file system entry at `path` is (symbolic links followed unless `follow` is false): unreadable when
// its status cannot be read (a loop of symbolic links).
enum class FileKind { regular, directory, symlink, block, character, fifo, socket, missing, unreadable, other };
FileKind file_kind(const std::string& path, bool follow = true);
// The same in words ("a regular file", "a FIFO (named pipe)", "unreadable (Too many levels of symbolic links)").
std::string file_type_name(const std::string& path, bool follow = true);

}  // namespace rondel
