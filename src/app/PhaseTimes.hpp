#pragma once
#include <array>
#include <chrono>
#include <string>

namespace rondel {

// Where a rank's wall time goes, phase by phase (seconds, this rank, waiting for other ranks included):
//   force: body forces, the contact kernel and the per-disc sums; neighbour: the displacement check and the
//   list build; communication: ghost updates, migration and the step's reductions; integrate: kicks, drift
//   and walls; output: diagnostics, measures, snapshots and checkpoints; other: the rest of the loop.
// A lap is one steady_clock read that books the time since the previous one: a few per step, none per disc.
class PhaseTimes {
 public:
  enum Phase { force, neighbour, communication, integrate, output, other, count };

  // The next lap starts now (the time before it is booked to no phase).
  void restart() { last_ = std::chrono::steady_clock::now(); }
  void lap(Phase p) {
    const auto now = std::chrono::steady_clock::now();
    seconds_[p] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  double seconds(Phase p) const { return seconds_[p]; }
  static const char* name(Phase p) {
    static constexpr const char* names[] = {"force", "neighbour", "communication", "integrate", "output", "other"};
    return names[p];
  }
  // "phases: force 61 %, neighbour 9 %, ..." of the time booked since `start` (an earlier copy).
  std::string line_since(const PhaseTimes& start) const;

 private:
  std::array<double, count> seconds_{};
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace rondel
