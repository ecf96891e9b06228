#include "core/StopSignal.hpp"

namespace rondel {

namespace {
volatile std::sig_atomic_t g_received = 0;
extern "C" void record_signal(int signal) { g_received = signal; }
}  // namespace

void StopSignal::install() {
  std::signal(SIGTERM, record_signal);
  std::signal(SIGINT, record_signal);
  std::signal(SIGUSR1, record_signal);
}

int StopSignal::received() { return g_received; }

const char* StopSignal::name(int signal) {
  switch (signal) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGUSR1:
      return "SIGUSR1";
    default:
      return "a signal";
  }
}

}  // namespace rondel
