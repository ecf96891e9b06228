#include "core/FaultInjection.hpp"

#include <cstdint>
#include <cstdlib>
#include <map>

namespace rondel {

namespace {

struct Fault {
  std::string site;
  int rank = -1;          // -1: every rank
  std::int64_t from = 1;  // the visit (or file) from which it fires
  bool set = false;
};

// Parses RONDEL_FAULT once; a malformed value injects nothing (it is a test hook, not an input).
const Fault& fault() {
  static const Fault f = [] {
    Fault out;
    const char* env = std::getenv("RONDEL_FAULT");
    if (!env || !*env) return out;
    std::string s = env;
    if (const auto hash = s.find('#'); hash != std::string::npos) {
      out.from = std::atoll(s.c_str() + hash + 1);
      s.resize(hash);
    }
    if (const auto at = s.find('@'); at != std::string::npos) {
      out.rank = std::atoi(s.c_str() + at + 1);
      s.resize(at);
    }
    out.site = s;
    out.set = !s.empty() && out.from >= 1;
    return out;
  }();
  return f;
}

std::map<std::string, std::int64_t>& visits() {
  static std::map<std::string, std::int64_t> v;
  return v;
}

bool counts_files(const std::string& site) { return site == "hdf5_write" || site == "hdf5_close"; }

}  // namespace

bool injected_fault(const std::string& site, int rank) {
  const Fault& f = fault();
  if (!f.set || f.site != site || (f.rank >= 0 && f.rank != rank)) return false;
  if (counts_files(site)) return visits()["file"] >= f.from;
  return ++visits()[site] >= f.from;
}

void injected_fault_new_file(int rank) {
  const Fault& f = fault();
  if (f.set && counts_files(f.site) && (f.rank < 0 || f.rank == rank)) ++visits()["file"];
}

}  // namespace rondel
