// rondel: a 2D discrete element code for discs. Usage: mpirun -n N rondel FILE.ini [--section.key=value ...]
#include <cstdio>
#include <exception>
#include <iostream>

#include "Simulation.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  rondel::Communicator comm;
  // Exit codes: 0 done, 1 configuration or input error, 3 the run became unstable, 4 internal error.
  try {
    rondel::Config config = rondel::parse_config(argc, argv);
    rondel::Simulation sim(std::move(config), comm);
    sim.run();
    return 0;
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
