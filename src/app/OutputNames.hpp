#pragma once
// The names of the files of an output directory (run.output; README "Output files"), their one home: RunFiles
// writes them, the fault site text:NAME takes them (core/FaultInjection.hpp), Checkpointing names its own.
namespace rondel::output {

inline constexpr const char* kConfig = "config.ini";
inline constexpr const char* kLog = "log.txt";
inline constexpr const char* kDiagnostics = "diagnostics.csv";
inline constexpr const char* kMeasures = "measures.csv";
inline constexpr const char* kFinal = "final.csv";
inline constexpr const char* kSummaryText = "summary.txt";
inline constexpr const char* kSummaryJson = "summary.json";
inline constexpr const char* kLock = "rondel.lock";
// The line of config.ini that names the run (its id, also in every checkpoint: a checkpoint of another run found
// in the directory is passed over by --resume).
inline constexpr const char* kRunIdComment = "# run id: ";
// The HDF5 files: <kind>_<step>.h5 (Checkpointing::file_name), a checkpoint written under a hidden name first, and
// the snapshots' XDMF side-car (written as a hidden part, then renamed).
inline constexpr const char* kCheckpoint = "checkpoint";
inline constexpr const char* kSnapshot = "snapshot";
inline constexpr const char* kStateExtension = ".h5";
inline constexpr const char* kHiddenCheckpoint = ".checkpoint_";
inline constexpr const char* kXdmf = "snapshots.xdmf";
inline constexpr const char* kXdmfPart = ".snapshots.xdmf.part";
// The text files, in the order a run opens them.
inline constexpr const char* kTextFiles[] = {kConfig, kLog,         kDiagnostics, kMeasures,
                                             kFinal,  kSummaryText, kSummaryJson};

}  // namespace rondel::output
