#include "app/Launch.hpp"

#include <algorithm>
#include <cstdint>
#include <iostream>

#include "app/Checkpointing.hpp"
#include "app/OutputNames.hpp"
#include "core/Errors.hpp"
#include "core/FaultInjection.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/StateFile.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

namespace {

// The --resume directory, if any, and whether an INI file was named.
std::string resume_directory(const std::vector<std::string>& args, bool& has_file) {
  std::string dir;
  has_file = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--resume" && i + 1 < args.size())  // read before the configuration, which it may come from
      dir = args[++i];
    else if (a.rfind("--resume=", 0) == 0)
      dir = a.substr(9);
    else if (a.rfind("--", 0) != 0)
      has_file = true;
  }
  return dir;
}

// A resumed run has work to do only below run.steps: at it there is nothing to do (true: say so and stop),
// above it the configuration is wrong.
bool nothing_to_resume(const Config& config, const std::string& checkpoint, std::int64_t step) {
  if (config.steps > step) return false;
  if (config.steps < step)
    throw ConfigError("run.steps = " + std::to_string(config.steps) + " is below the step " + std::to_string(step) +
                      " of the checkpoint '" + checkpoint +
                      "' to resume from; run.steps counts from the start of the run: set run.steps > " +
                      std::to_string(step) + " to continue it");
  return true;
}

}  // namespace

Launch prepare_launch(const LaunchArgs& in, const Communicator& comm) {
  Launch s;
  bool has_file = false;
  const std::string resume = resume_directory(in.args, has_file);
  has_file = has_file || in.ini_text != nullptr;
  StateHeader header;
  if (!resume.empty()) {
    std::vector<std::string> skipped;
    agree(comm, [&] { s.checkpoint = Checkpointing::newest_checkpoint(resume, comm, &skipped); });
    if (comm.root())
      for (const auto& k : skipped) std::cerr << "rondel: skipping " << k << '\n';
    agree(comm, [&] { header = read_state_header(s.checkpoint, comm); });
  }
  // A fault-injection hook that injects nothing is refused before any work (core/FaultInjection.hpp).
  agree(comm, [] { check_fault_injection(output::kTextFiles); });
  agree(comm, [&] {
    if (!resume.empty() && !has_file) {
      // No INI: the configuration stored in the checkpoint, with the overrides.
      // It continues in DIR itself, unless the arguments name another run.output.
      std::vector<std::string> args = in.args;
      const bool named =
          std::any_of(args.begin(), args.end(), [](const std::string& a) { return a.rfind("--run.output", 0) == 0; });
      if (!named) args.push_back("--run.output=" + resume);
      s.config = parse_config_text(header.config, args);
    } else if (in.ini_text != nullptr) {
      s.config = parse_config_text(*in.ini_text, in.args);
    } else {
      std::vector<const char*> argv{"rondel"};
      for (const auto& a : in.args) argv.push_back(a.c_str());
      s.config = parse_config(static_cast<int>(argv.size()), argv.data());
    }
    s.nothing_to_do = !resume.empty() && nothing_to_resume(s.config, s.checkpoint, header.step);
  });
  return s;
}

std::string nothing_to_do_message(const Launch& launch) {
  return "rondel: nothing to do: the checkpoint '" + launch.checkpoint + "' is at step " +
         std::to_string(launch.config.steps) +
         " = run.steps already (the run is complete); raise run.steps (--run.steps=N) to continue it";
}

}  // namespace rondel
