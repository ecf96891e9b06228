// A program built against an installed Rondel (find_package(Rondel), Rondel::app): parses a configuration
// with the law registry and prints the rolling laws, so that the test sees the headers, the libraries and
// their dependencies work from the install prefix. Exit 0 when the parsed values are the given ones.
#include <cstdio>
#include <exception>
#include <string>

#include "app/Simulation.hpp"
#include "physics/LawRegistry.hpp"

int main() {
  const std::string ini =
      "[run]\nsteps = 10\n"
      "[domain]\nxlo = 0\nxhi = 1\nylo = 0\nyhi = 1\n"
      "[linear]\nk_n = 1e5\n"
      "[coulomb]\nk_s = 5e4\nmu = 0.5\n"
      "[scene]\ntype = lattice_square\nnx = 2\nny = 2\nradius = 0.1\nspacing = 0.25\nx0 = 0.25\ny0 = 0.25\n";
  try {
    const rondel::Config c = rondel::parse_config_text(ini, {"--contact.rolling=none"});
    std::printf("rolling laws: %s\n", rondel::law_catalog().rolling.keywords().c_str());
    std::printf("steps %lld, normal law %s\n", static_cast<long long>(c.steps), c.normal_law.c_str());
    return c.steps == 10 && c.normal_law == "linear" ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rondel_consumer: %s\n", e.what());
    return 1;
  }
}
