#pragma once
// Failures injected on purpose, for the tests of the I/O error paths (docs/developing.md "Injected faults"): a
// disk that fills on one rank only, a close that fails, a text output that does not reach the disk. Off unless
// the environment variable RONDEL_FAULT is set; never set it for a production run.
//
//   RONDEL_FAULT=SITE[@RANK][#N]
//
// SITE is one of kFaultSites. The fault fires on the rank RANK (every rank when absent), from the N-th time that
// rank reaches the site on (1 when absent): `hdf5_write@2#3` lets rank 2 write two files and fails every dataset
// write of the third and later ones (the sites that count files count files, the others calls). A value that
// names no site, a text file the run does not write, or a malformed rank or count is an error before any work
// (check_fault_injection): a misspelt fault that injected nothing would pass a test that should have failed.
#include <span>
#include <string>
#include <vector>

namespace rondel {

enum class FaultSite { hdf5_write, hdf5_close, reserve, text, alloc, setup_pause };

struct FaultSiteInfo {
  FaultSite site;
  const char* name;   // as RONDEL_FAULT names it (text: "text:" and the file's name)
  bool counts_files;  // #N counts the HDF5 files the rank creates, not the visits of the site
  const char* help;
};

inline constexpr FaultSiteInfo kFaultSites[] = {
    {FaultSite::hdf5_write, "hdf5_write", true, "every dataset write of an HDF5 file (checkpoint or snapshot)"},
    {FaultSite::hdf5_close, "hdf5_close", true, "the metadata flush before an HDF5 file is closed"},
    {FaultSite::reserve, "reserve", false, "the space reservation of an HDF5 file (rank 0), as a full disk would"},
    {FaultSite::text, "text:", false, "text:NAME, the text file NAME of the output directory"},
    {FaultSite::alloc, "alloc", false,
     "an allocation (std::bad_alloc) where final.csv is formatted, as an exhausted memory would"},
    {FaultSite::setup_pause, "setup_pause", false,
     "no failure: set-up waits (at most a minute) for a stop signal before the first file is written"},
};

// Whether the fault at `site` fires now on this process's rank `rank` (counts one visit of the site); `file`:
// the text file's name (FaultSite::text).
bool injected_fault(FaultSite site, int rank, const std::string& file = "");

// For the sites that count files: marks the start of a new file of this rank.
void injected_fault_new_file(int rank);

// Throws ConfigError naming RONDEL_FAULT and what is allowed when it is set to anything but a site of kFaultSites
// (`text_files`: the names text:NAME may take) with an optional @RANK (>= 0) and #N (>= 1).
void check_fault_injection(std::span<const char* const> text_files);

}  // namespace rondel
