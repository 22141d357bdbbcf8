#include "mpi/group.hpp"

#include <cstdio>
#include <cstdlib>

namespace lzb::mpi {

void check(int code, const char* call, const char* file, int line) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw Error(std::string(call) + " failed at " + file + ":" + std::to_string(line) + ": " +
              std::string(text, size_t(length)));
}

Group Group::world() {
  Group g;
  LZB_MPI_CALL(MPI_Comm_rank(g.comm, &g.rank));
  LZB_MPI_CALL(MPI_Comm_size(g.comm, &g.size));
  return g;
}

Session::Session(int* argc, char*** argv) {
  int provided = 0;
  // Only the main thread calls MPI; OpenMP threads never do.
  LZB_MPI_CALL(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided));
  if (provided < MPI_THREAD_FUNNELED) {
    // Every rank links the same MPI library, so every rank stops here alike.
    std::fprintf(stderr, "lzb: error: the MPI library provides thread level %d; lzb needs "
                 "MPI_THREAD_FUNNELED (%d) for its OpenMP threads\n", provided, MPI_THREAD_FUNNELED);
    MPI_Finalize();
    std::exit(1);
  }
  // Errors come back as codes so LZB_MPI_CALL can turn them into exceptions.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

Session::~Session() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

}  // namespace lzb::mpi
