// main() of the multi-rank test programs (tests/mpi/): MPI for the process's lifetime, gtest's
// report from rank 0 only (every rank runs every test and fails on its own), and a job that
// fails if any rank failed.
#include <gtest/gtest.h>
#include <mpi.h>

#include "parallel/comm.hpp"

int main(int argc, char** argv) {
  swell::parallel::Environment env(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (swell::parallel::Comm::world().rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int rc = RUN_ALL_TESTS();
  int worst = rc;
  MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return worst;
}
