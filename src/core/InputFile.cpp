#include "core/InputFile.hpp"

#include <filesystem>
#include <system_error>

namespace rondel {

namespace fs = std::filesystem;

FileKind file_kind(const std::string& path, bool follow) {
  std::error_code ec;
  const fs::file_status s = follow ? fs::status(path, ec) : fs::symlink_status(path, ec);
  switch (s.type()) {
    case fs::file_type::regular:
      return FileKind::regular;
    case fs::file_type::directory:
      return FileKind::directory;
    case fs::file_type::symlink:
      return FileKind::symlink;
    case fs::file_type::block:
      return FileKind::block;
    case fs::file_type::character:
      return FileKind::character;
    case fs::file_type::fifo:
      return FileKind::fifo;
    case fs::file_type::socket:
      return FileKind::socket;
    case fs::file_type::not_found:
      return FileKind::missing;
    default:
      return ec ? FileKind::unreadable : FileKind::other;
  }
}

std::string file_type_name(const std::string& path, bool follow) {
  switch (file_kind(path, follow)) {
    case FileKind::regular:
      return "a regular file";
    case FileKind::directory:
      return "a directory";
    case FileKind::symlink:
      return "a symbolic link";
    case FileKind::block:
      return "a block device";
    case FileKind::character:
      return "a character device";
    case FileKind::fifo:
      return "a FIFO (named pipe)";
    case FileKind::socket:
      return "a socket";
    case FileKind::missing:
      return "missing";
    case FileKind::unreadable: {
      std::error_code ec;
      (void)(follow ? fs::status(path, ec) : fs::symlink_status(path, ec));
      return "unreadable (" + ec.message() + ")";
    }
    case FileKind::other:
      break;
  }
  return "not a regular file";
}

std::string input_file_problem(const std::string& path, const std::string& what, std::uint64_t max_bytes) {
  const FileKind kind = file_kind(path);
  if (kind == FileKind::missing) return "cannot read " + what + " '" + path + "': it does not exist";
  if (kind == FileKind::directory) return what + " '" + path + "' is a directory, not a file";
  if (kind != FileKind::regular)
    return what + " '" + path + "' is " + file_type_name(path) +
           ", not a regular file (a device or a pipe would be read without end)";
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return what + " '" + path + "' cannot be read (" + ec.message() + ")";
  if (size > max_bytes)
    return what + " '" + path + "' has " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes) +
           " bytes such a file may have";
  return "";
}

}  // namespace rondel
