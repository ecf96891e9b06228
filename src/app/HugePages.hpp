#pragma once
// Large allocations in transparent huge pages (docs/scaling.md, "Huge pages"). Most of a large set-up's time on a
// virtual machine can be the kernel's first touch of fresh 4 KiB pages (1.5 million page faults, 15 s of 31, for
// ten million discs on one rank here); glibc's malloc asks for huge pages when its tunable glibc.malloc.hugetlb = 1
// is set, which it reads only when a process starts.

namespace rondel {

// Called first in main, before MPI starts: when huge pages would help (the kernel offers them on request, glibc
// knows the tunable, RONDEL_HUGE_PAGES is not 0) and the tunable is not yet set, sets it in GLIBC_TUNABLES (after
// any tunables there) and runs the program again (execv of /proc/self/exe, the same arguments), so that every
// allocation of the run, MPI's and HDF5's too, may use them. Not under valgrind (it would not follow). Returns when
// it does not run the program again (nothing to do, or the exec failed: the run goes on without). Returns false
// when RONDEL_HUGE_PAGES is neither 0 nor 1 (`why` says so): the caller refuses to start.
bool use_huge_pages(char** argv, const char*& why);

}  // namespace rondel
