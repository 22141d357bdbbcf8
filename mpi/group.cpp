#include "mpi/group.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

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

int ranksOnMachine(const Group& g) {
  MPI_Comm local;
  LZB_MPI_CALL(MPI_Comm_split_type(g.comm, MPI_COMM_TYPE_SHARED, g.rank, MPI_INFO_NULL, &local));
  int size = 1;
  LZB_MPI_CALL(MPI_Comm_size(local, &size));
  LZB_MPI_CALL(MPI_Comm_free(&local));
  return size;
}

SubGroups::SubGroups(const Group& parent, int count)
    : group_(parent), count_(count), parentSize_(parent.size) {
  if (count <= 1) return;
  index_ = int(int64_t(parent.rank) * count / parent.size);
  LZB_MPI_CALL(MPI_Comm_split(parent.comm, index_, parent.rank, &group_.comm));
  owned_ = true;
  LZB_MPI_CALL(MPI_Comm_rank(group_.comm, &group_.rank));
  LZB_MPI_CALL(MPI_Comm_size(group_.comm, &group_.size));
  // Errors come back as codes here too.
  MPI_Comm_set_errhandler(group_.comm, MPI_ERRORS_RETURN);
}

SubGroups::~SubGroups() {
  if (owned_) MPI_Comm_free(&group_.comm);
}

int SubGroups::rootOf(int k) const {
  // The smallest rank r with r * count / size == k.
  return int((int64_t(k) * parentSize_ + count_ - 1) / count_);
}

namespace {

// Whether a launcher (mpiexec, srun) started this process: it then owns the session folder.
bool launched() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK");
}

// A fresh folder under $TMPDIR (else /tmp) for a singleton's session files, named in Open MPI's
// MCA variable; empty when launched, when the user chose a folder, or when none can be made.
std::string privateSessionFolder() {
  if (launched() || std::getenv("OMPI_MCA_orte_tmpdir_base")) return "";
  const char* tmp = std::getenv("TMPDIR");
  std::string folder = std::string(tmp && *tmp ? tmp : "/tmp") + "/lzb-mpi-XXXXXX";
  if (!mkdtemp(folder.data())) return "";
  setenv("OMPI_MCA_orte_tmpdir_base", folder.c_str(), 1);
  return folder;
}

// A singleton runs alone: without a daemon (orted) of its own, which it would start only to spawn
// processes, as lzb never does, and without probing UCX's network devices for peers it does not
// have (ob1 over the self transport: 0.41 -> 0.18 s an `lzb info`). Unless the user chose
// otherwise.
void isolateSingleton() {
  if (launched()) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_osc", "^ucx", 0);
}

}  // namespace

Session::Session(int* argc, char*** argv, bool threadsCallMpi) : privateTmp_(privateSessionFolder()) {
  isolateSingleton();
  int provided = 0;
  // OpenMP threads never call MPI; only the node server's threads need more than FUNNELED.
  LZB_MPI_CALL(MPI_Init_thread(argc, argv, threadsCallMpi ? MPI_THREAD_MULTIPLE : MPI_THREAD_FUNNELED,
                               &provided));
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
  std::error_code ignored;  // a folder left behind is harmless
  if (!privateTmp_.empty()) std::filesystem::remove_all(privateTmp_, ignored);
}

}  // namespace lzb::mpi
