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

// The ranks of `g` on this rank's machine (those sharing its memory), this one included.
int ranksOnMachine(const Group& g);

// The ranks of `parent` cut into `count` contiguous groups of (nearly) equal size; this rank's
// group as a Group of its own (its communicator freed with this object). count 1: the parent.
class SubGroups {
 public:
  SubGroups(const Group& parent, int count);
  ~SubGroups();
  SubGroups(const SubGroups&) = delete;
  SubGroups& operator=(const SubGroups&) = delete;
  const Group& group() const { return group_; }
  int index() const { return index_; }  // this rank's group, 0..count-1
  int count() const { return count_; }
  // The parent rank of group k's root (its first rank).
  int rootOf(int k) const;

 private:
  Group group_;
  int index_ = 0, count_ = 1, parentSize_ = 1;
  bool owned_ = false;
};

// MPI_Init_thread on construction, MPI_Finalize on destruction (unless already finalized).
// threadsCallMpi asks for MPI_THREAD_MULTIPLE (a thread besides the main one calls MPI: the
// sample tree's node server and its clients' loaders); else MPI_THREAD_FUNNELED, which saves
// Open MPI's locking on every call. Either way at least FUNNELED is required.
// A process that no launcher started (a singleton) keeps Open MPI's session files in a folder of
// its own, removed on destruction: Open MPI 4.1 shares /tmp/ompi.<host>.<uid> between jobs, and a
// job ending removes it while another one starting creates it ("mkdir ... File exists", and
// MPI_Init fails), so two lzb commands started at once could fail.
class Session {
 public:
  Session(int* argc, char*** argv, bool threadsCallMpi = false);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

 private:
  std::string privateTmp_;  // the singleton's own session folder; empty when launched
};

}  // namespace lzb::mpi
