#pragma once
// Failures injected on purpose, for the tests of the I/O error paths (docs/developing.md "Injected
// faults"): a disk that fills on one rank only, a close that fails, a text output that does not reach the
// disk. Off unless the environment variable RONDEL_FAULT is set; never set it for a production run.
//
//   RONDEL_FAULT=SITE[@RANK][#N]
//
// SITE is `hdf5_write` (a dataset write of an HDF5 file), `hdf5_close` (closing an HDF5 file that was
// written), `reserve` (the space reserved for a file) or `text:NAME` (the text file NAME of the output
// directory, e.g. text:final.csv). The fault fires on the rank RANK (every rank when absent), from the N-th
// time that rank reaches the site on (1 when absent): `hdf5_write@2#3` lets rank 2 write two files and fails
// every dataset write of the third and later ones (for hdf5_write and hdf5_close N counts files, for the
// others calls).
#include <string>

namespace rondel {

// Whether the fault `site` fires now on this process's rank `rank` (counts one visit of the site).
bool injected_fault(const std::string& site, int rank);

// For hdf5_write: the files count, not the dataset writes; marks the start of a new file of this rank.
void injected_fault_new_file(int rank);

}  // namespace rondel
