#pragma once
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// What starts a run, from the executable's command line or the Python module's arguments: an INI file (or an
// INI text), `--section.key=value` overrides, and `--resume DIR` (the newest valid checkpoint of DIR; without an
// INI, the configuration stored in it, continuing in DIR unless run.output is overridden).
struct LaunchArgs {
  std::vector<std::string> args;  // as after the program name: [FILE.ini] [--resume DIR] [--section.key=value ...]
  const std::string* ini_text = nullptr;  // an INI text in place of FILE.ini (the module)
};

// The configuration and the checkpoint of a launch, each step agreed among the ranks (an error on one rank, a
// file it cannot read, stops every rank before the next collective): the one set-up before a Simulation.
struct Launch {
  Config config;
  std::string checkpoint;      // "" for a fresh run
  bool nothing_to_do = false;  // a resumed run whose checkpoint is at run.steps already
};

Launch prepare_launch(const LaunchArgs& in, const Communicator& comm);

// The line a resumed run with nothing to do prints.
std::string nothing_to_do_message(const Launch& launch);

}  // namespace rondel
