#include "core/FileSpace.hpp"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace rondel {

namespace {
std::string megabytes(double bytes) {
  char text[32];
  if (bytes < 1e6)
    std::snprintf(text, sizeof text, "%.0f kB", bytes / 1e3);
  else
    std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
  return text;
}
}  // namespace

std::string reserve_file_space(const std::string& path, std::uint64_t bytes, bool injected) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT, 0644);
  if (fd < 0) return std::string("cannot create it: ") + std::strerror(errno);
  int rc = injected ? ENOSPC : 0;
#ifdef __linux__
  if (rc == 0 && bytes > 0 && ::fallocate(fd, 0, 0, static_cast<off_t>(bytes)) != 0) rc = errno;
#endif
  ::close(fd);
  if (rc == 0 || rc == EOPNOTSUPP || rc == ENOSYS || rc == EINVAL) return "";
  std::string why = std::strerror(rc);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  struct statvfs fs {};
  if (statvfs(dir.empty() ? "." : dir.c_str(), &fs) == 0)
    why += " (it needs about " + megabytes(static_cast<double>(bytes)) + "; " +
           megabytes(static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize)) + " free)";
  return why;
}

}  // namespace rondel
