#pragma once
// A thin MPI layer: the communicator with its rank and size, and a checked-call macro.
#include <mpi.h>

#include <stdexcept>
#include <string>

namespace lzb::mpi {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws mpi::Error with MPI's own message when an MPI call fails.
void check(int code, const char* call, const char* file, int line);
#define LZB_MPI_CALL(call) ::lzb::mpi::check((call), #call, __FILE__, __LINE__)

struct Group {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0;
  int size = 1;

  static Group world();
  bool root() const { return rank == 0; }
  void barrier() const { LZB_MPI_CALL(MPI_Barrier(comm)); }
};

// MPI_Init_thread on construction, MPI_Finalize on destruction (unless already finalized).
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

}  // namespace lzb::mpi
