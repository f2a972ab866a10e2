// A failure on one rank only, under the MPI commands' MpiSession::run: rank 1 throws while every
// other rank waits in a barrier for it. MPI_Finalize would wait there too, so the job must end by
// the abort, with the failing rank named (mpi_failures.sh checks both).
#include <mpi.h>

#include <exception>
#include <iostream>
#include <stdexcept>

#include "mpi_session.hpp"

int main() {
  try {
    const sedwave::app::MpiSession mpi;
    return mpi.run([&] {
      if (mpi.rank() == 1) throw std::runtime_error("only rank 1 fails");
      MPI_Barrier(MPI_COMM_WORLD);
      return 0;
    });
  } catch (...) {
    return sedwave::app::report_failure(std::current_exception(), &std::cerr);
  }
}
