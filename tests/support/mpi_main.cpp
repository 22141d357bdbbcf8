// The main of the GoogleTest programs run under mpiexec: MPI started before the tests, and the
// verdict agreed on by every rank, or mpiexec could report success for a failing rank.
#include <gtest/gtest.h>

#include "mpi/group.hpp"

int main(int argc, char** argv) {
  lzb::mpi::Session session(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int failed = RUN_ALL_TESTS();
  int anyFailed = 0;
  MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return anyFailed;
}
