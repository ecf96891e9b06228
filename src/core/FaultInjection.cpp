#include "core/FaultInjection.hpp"

#include <cstdint>
#include <cstdlib>
#include <map>

#include "core/Errors.hpp"

namespace rondel {

namespace {

struct Fault {
  const FaultSiteInfo* site = nullptr;
  std::string file;       // text:NAME
  int rank = -1;          // -1: every rank
  std::int64_t from = 1;  // the visit (or file) from which it fires
  std::string error;      // why the value is not a fault ("" when it is one, or when none is set)
};

// A whole number >= lo, or -1.
long long whole(const std::string& s, long long lo) {
  char* end = nullptr;
  const long long v = s.empty() ? -1 : std::strtoll(s.c_str(), &end, 10);
  return !s.empty() && end == s.c_str() + s.size() && v >= lo ? v : -1;
}

Fault parse(std::string s) {
  Fault out;
  if (const auto hash = s.find('#'); hash != std::string::npos) {
    out.from = whole(s.substr(hash + 1), 1);
    if (out.from < 1) out.error = "#N must be a whole number >= 1";
    s.resize(hash);
  }
  if (const auto at = s.find('@'); at != std::string::npos) {
    out.rank = static_cast<int>(whole(s.substr(at + 1), 0));
    if (out.rank < 0) out.error = "@RANK must be a whole number >= 0";
    s.resize(at);
  }
  for (const FaultSiteInfo& site : kFaultSites)
    if (site.site == FaultSite::text ? s.rfind(site.name, 0) == 0 : s == site.name) out.site = &site;
  if (out.site && out.site->site == FaultSite::text) out.file = s.substr(std::string(out.site->name).size());
  if (!out.site && out.error.empty()) out.error = "'" + s + "' is not a fault site";
  return out;
}

// Parses RONDEL_FAULT once (check_fault_injection refuses a value that is not a fault before any work).
const Fault& fault() {
  static const Fault f = [] {
    const char* env = std::getenv("RONDEL_FAULT");
    return env && *env ? parse(env) : Fault{};
  }();
  return f;
}

std::map<std::string, std::int64_t>& visits() {
  static std::map<std::string, std::int64_t> v;
  return v;
}

}  // namespace

bool injected_fault(FaultSite site, int rank, const std::string& file) {
  const Fault& f = fault();
  if (!f.site || !f.error.empty() || f.site->site != site || (f.rank >= 0 && f.rank != rank)) return false;
  if (site == FaultSite::text && f.file != file) return false;
  if (f.site->counts_files) return visits()["file"] >= f.from;
  return ++visits()[f.site->name] >= f.from;
}

void injected_fault_new_file(int rank) {
  const Fault& f = fault();
  if (f.site && f.site->counts_files && (f.rank < 0 || f.rank == rank)) ++visits()["file"];
}

void check_fault_injection(std::span<const char* const> text_files) {
  const char* env = std::getenv("RONDEL_FAULT");
  if (!env || !*env) return;
  const Fault& f = fault();
  std::string why = f.error;
  if (why.empty() && f.site->site == FaultSite::text) {
    bool known = false;
    for (const char* name : text_files) known = known || f.file == name;
    if (!known) why = "'" + f.file + "' is not a text file of the output directory";
  }
  if (why.empty()) return;
  std::string sites, files;
  for (const FaultSiteInfo& site : kFaultSites) sites += (sites.empty() ? "" : ", ") + std::string(site.name);
  for (const char* name : text_files) files += (files.empty() ? "" : " ") + std::string(name);
  throw ConfigError("the environment variable RONDEL_FAULT = '" + std::string(env) + "' injects no fault: " + why +
                    "; allowed: SITE[@RANK][#N] with SITE one of " + sites + " (text:NAME with NAME one of " + files +
                    "), a test hook (docs/developing.md, \"Injected faults\"): unset it for a run");
}

}  // namespace rondel
