// rondel: a 2D discrete element code for discs.
//   mpirun -n N rondel FILE.ini [--section.key=value ...]
//   mpirun -n N rondel [FILE.ini] --resume OUTPUT_DIR [--section.key=value ...]
//   rondel --version | --help
#include <algorithm>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "app/Checkpointing.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "rondel/Version.hpp"

namespace {

// The --resume directory, if any, and whether an INI file was named.
std::string resume_directory(int argc, char** argv, bool& has_file) {
  std::string dir;
  has_file = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--resume" && i + 1 < argc)
      dir = argv[++i];
    else if (a.rfind("--resume=", 0) == 0)
      dir = a.substr(9);
    else if (a.rfind("--", 0) != 0)
      has_file = true;
  }
  return dir;
}

bool version_requested(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--version") == 0) return true;
  return false;
}

// A resumed run has work to do only below run.steps: at it there is nothing to do (true: say so and stop),
// above it the configuration is wrong.
bool nothing_to_resume(const rondel::Config& config, const std::string& checkpoint, std::int64_t step) {
  if (config.steps > step) return false;
  if (config.steps < step)
    throw rondel::ConfigError("run.steps = " + std::to_string(config.steps) + " is below the step " +
                              std::to_string(step) + " of the checkpoint '" + checkpoint +
                              "' to resume from; run.steps counts from the start of the run: set run.steps > " +
                              std::to_string(step) + " to continue it");
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  rondel::Communicator comm;
  // Exit codes: 0 done (also --help, --version, and a --resume with nothing to do, with a notice),
  // 1 configuration or input error, 3 the run became unstable, 4 internal error, 10 stopped by SIGTERM,
  // SIGINT or SIGUSR1 after writing a checkpoint (continue with --resume).
  if (version_requested(argc, argv)) {
    if (comm.root()) std::cout << "rondel " << rondel::kRondelVersion << " (commit " << rondel::kRondelCommit << ")\n";
    return 0;
  }
  try {
    bool has_file = false;
    const std::string resume = resume_directory(argc, argv, has_file);
    std::string checkpoint;
    rondel::Config config;
    if (!resume.empty()) {
      std::vector<std::string> skipped;
      checkpoint = rondel::Checkpointing::newest_checkpoint(resume, comm, &skipped);
      if (comm.root())
        for (const auto& s : skipped) std::cerr << "rondel: skipping " << s << '\n';
    }
    if (!resume.empty() && !has_file) {
      // No INI: the configuration stored in the checkpoint, with the command line's overrides.
      // It continues in DIR itself, unless the command line names another run.output.
      std::vector<std::string> args(argv + 1, argv + argc);
      const bool named =
          std::any_of(args.begin(), args.end(), [](const std::string& a) { return a.rfind("--run.output", 0) == 0; });
      if (!named) args.push_back("--run.output=" + resume);
      config = rondel::parse_config_text(rondel::read_state_header(checkpoint, comm).config, args);
    } else {
      config = rondel::parse_config(argc, argv);
    }
    if (!resume.empty() && nothing_to_resume(config, checkpoint, rondel::read_state_header(checkpoint, comm).step)) {
      if (comm.root())
        std::cout << "rondel: nothing to do: the checkpoint '" << checkpoint << "' is at step " << config.steps
                  << " = run.steps already (the run is complete); raise run.steps (--run.steps=N) to continue it\n";
      return 0;
    }
    rondel::Simulation sim(std::move(config), comm, true, checkpoint);
    const rondel::RunSummary summary = sim.run();
    return summary.stop_signal != 0 ? 10 : 0;
  } catch (const rondel::HelpRequested& h) {
    if (comm.root()) std::cout << h.text;
    return 0;
  } catch (const rondel::ConfigError& e) {
    if (comm.root()) std::cerr << "rondel: configuration error: " << e.what() << '\n';
    return 1;
  } catch (const rondel::InputError& e) {
    if (comm.root()) std::cerr << "rondel: input error: " << e.what() << '\n';
    return 1;
  } catch (const rondel::InstabilityError& e) {
    if (comm.root()) std::cerr << "rondel: the run became unstable: " << e.what() << '\n';
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "rondel: internal error: " << e.what() << '\n';
    return 4;
  }
}
