#include "app/HugePages.hpp"

#include <gnu/libc-version.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace rondel {

namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=1";

// The kernel's transparent huge pages: "always" (malloc gets them anyway) or "madvise" (only on request).
bool on_request() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(in, modes);
  return modes.find("[madvise]") != std::string::npos;
}

// glibc 2.35 and later know glibc.malloc.hugetlb.
bool glibc_knows() {
  int major = 0, minor = 0;
  return std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) == 2 && (major > 2 || minor >= 35);
}

bool under_valgrind() {
  const char* preload = std::getenv("LD_PRELOAD");
  return preload != nullptr && std::strstr(preload, "vgpreload") != nullptr;
}

}  // namespace

bool use_huge_pages(char** argv, const char*& why) {
  const char* wanted = std::getenv("RONDEL_HUGE_PAGES");
  if (wanted != nullptr && std::strcmp(wanted, "0") != 0 && std::strcmp(wanted, "1") != 0) {  // the allowed values
    why = "the environment variable RONDEL_HUGE_PAGES must be 0 (no huge pages) or 1 (the default)";
    return false;
  }
  if (wanted != nullptr && std::strcmp(wanted, "0") == 0) return true;  // asked not to
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.hugetlb") != nullptr) return true;  // set already
  if (!on_request() || !glibc_knows() || under_valgrind()) return true;
  const std::string value =
      tunables != nullptr && *tunables != '\0' ? std::string(tunables) + ":" + kTunable : kTunable;
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return true;
  execv("/proc/self/exe", argv);
  return true;  // the exec failed: on without huge pages
}

}  // namespace rondel
