#pragma once
// MPI for the benchmarks that run as one process. Each reads its whole packing and hands it to the
// engines as the only rank's, so under `mpirun -np P` with P > 1 the engines would see every grain
// P times (a Hertz packing's stiffness, for one, would come out wrong). OneProcessMpi starts MPI
// and refuses more than one rank; its end finalises MPI on every return path.
#include <mpi.h>

#include <cstdio>

namespace sedwave::bench {

class OneProcessMpi {
 public:
  OneProcessMpi(int& argc, char**& argv, const char* program) {
    MPI_Init(&argc, &argv);
    int size = 1, rank = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    alone_ = size == 1;
    if (!alone_ && rank == 0) {
      std::fprintf(stderr, "%s: runs as one process (it reads the whole packing); start it without mpirun -np %d\n",
                   program, size);
    }
  }
  ~OneProcessMpi() { MPI_Finalize(); }
  OneProcessMpi(const OneProcessMpi&) = delete;
  OneProcessMpi& operator=(const OneProcessMpi&) = delete;
  /// False under more than one rank: the caller returns at once, with exit status 2.
  [[nodiscard]] bool alone() const { return alone_; }

 private:
  bool alone_ = true;
};

}  // namespace sedwave::bench
