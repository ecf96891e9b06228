#pragma once
// The parallel bonds in the run's files (docs/bonds.md, FORMAT.md): a snapshot's /bonds as line segments between
// the bonded discs' centres with their forces and stresses, and /breaks, the breaks since the last snapshot (also in
// checkpoints, so that a resumed run writes them into its next snapshot). The columns are named here once, for the
// writer, the XDMF side-car and the reader.
#include <cstdint>
#include <string>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "physics/BondPass.hpp"

namespace rondel::bond_records {

// The columns: a snapshot's bonds (reals, beside the segment's ends end1 and end2), and a break's.
inline constexpr const char* kSegmentReals[] = {"Fb_n", "Fb_s", "Mb", "sigma", "tau"};
inline constexpr const char* kBreakReals[] = {"sigma", "tau"};
inline constexpr const char* kBreakIntegers[] = {"step", "mode"};
inline constexpr const char* kBreakPosition = "position";

// The bonds this rank books (disc 1 owned), as segments from disc 1's centre to disc 2's image beside it, with
// their forces and the stresses of their breaking test: sigma = Fb_n/A + |Mb| Rb/I [Pa], tau = |Fb_s|/A [Pa].
RecordTable segments(const BondContext& c, const ContactTable& bonds);

// Breaks as records (mode 1 tension, 2 shear).
RecordTable breaks(const std::vector<BondBreak>& records);

// This rank's block of a checkpoint's /breaks (the breaks not yet in a snapshot), appended to `out`. Collective.
void read_breaks(const std::string& path, std::vector<BondBreak>& out, const Communicator& comm);

}  // namespace rondel::bond_records
