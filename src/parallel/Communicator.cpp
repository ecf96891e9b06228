#include "parallel/Communicator.hpp"

namespace rondel {

MpiEnvironment::MpiEnvironment(int* argc, char*** argv) {
  int ready = 0;
  MPI_Initialized(&ready);
  if (!ready) MPI_Init(argc, argv);
}

MpiEnvironment::~MpiEnvironment() {
  int done = 0;
  MPI_Finalized(&done);
  if (!done) MPI_Finalize();
}

Communicator::Communicator(MPI_Comm comm) : comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

double Communicator::max(double local) const {
  double out = local;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return out;
}

double Communicator::sum(double local) const {
  double out = local;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return out;
}

std::int64_t Communicator::sum(std::int64_t local) const {
  std::int64_t out = local;
  MPI_Allreduce(&local, &out, 1, MPI_INT64_T, MPI_SUM, comm_);
  return out;
}

bool Communicator::any(bool local) const {
  int in = local ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, comm_);
  return out != 0;
}

void Communicator::barrier() const { MPI_Barrier(comm_); }

}  // namespace rondel
