#include "mpi/failure.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <thread>
#include <vector>

#include "mpi/collectives.hpp"
#include "src/core/error.hpp"

namespace lzb::mpi {

int statusOf(const std::exception& e) {
  return dynamic_cast<const InputError*>(&e) ? 2 : 1;
}

std::string messageOf(const std::exception& e) {
  return (statusOf(e) == 2 ? "error: " : "internal error: ") + std::string(e.what());
}

namespace {

// The worst status over ranks (0: all succeeded). A failed rank waits at most kAgreeSeconds.
int agreeOnStatus(const Group& g, int mine) {
  int worst = 0;
  MPI_Request request;
  LZB_MPI_CALL(MPI_Iallreduce(&mine, &worst, 1, MPI_INT, MPI_MAX, g.comm, &request));
  if (mine == 0) {
    LZB_MPI_CALL(MPI_Wait(&request, MPI_STATUS_IGNORE));
    return worst;
  }
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(kAgreeSeconds);
  for (;;) {
    int done = 0;
    LZB_MPI_CALL(MPI_Test(&request, &done, MPI_STATUS_IGNORE));
    if (done) return worst;
    if (std::chrono::steady_clock::now() > deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

void agree(const Group& g, const std::function<void()>& step) {
  int status = 0;
  std::string message;
  try {
    step();
  } catch (const JobFailed& e) {
    status = e.status;  // a step agreed on inside this one: its message is printed already
  } catch (const std::exception& e) {
    status = statusOf(e);
    message = messageOf(e);
  }
  if (g.size == 1) {
    if (status == 0) return;
    if (!message.empty()) std::fprintf(stderr, "lzb: %s\n", message.c_str());
    throw JobFailed(status);
  }
  const int worst = agreeOnStatus(g, status);
  if (worst < 0) {  // the other ranks are elsewhere: end them
    std::fprintf(stderr, "lzb: rank %d: %s\n", g.rank, message.c_str());
    std::fflush(stderr);
    MPI_Abort(g.comm, status);
  }
  if (worst == 0) return;
  // Every rank is here: the root prints each distinct message once, naming the ranks only when
  // they did not all fail alike.
  const std::vector<std::string> messages = gatherStrings(g, message);
  if (g.root()) {
    std::set<std::string> distinct;
    int failed = 0;
    for (const std::string& m : messages)
      if (!m.empty()) distinct.insert(m), ++failed;
    for (int r = 0; r < g.size; ++r) {
      const std::string& m = messages[size_t(r)];
      if (m.empty() || !distinct.erase(m)) continue;
      if (failed == g.size)
        std::fprintf(stderr, "lzb: %s\n", m.c_str());
      else
        std::fprintf(stderr, "lzb: rank %d: %s\n", r, m.c_str());
    }
  }
  throw JobFailed(worst);
}

void abortJob(const Group& g, const std::exception& e) {
  std::fprintf(stderr, "lzb: rank %d: %s\n", g.rank, messageOf(e).c_str());
  std::fflush(stderr);
  MPI_Abort(g.comm, statusOf(e));
  std::abort();  // MPI_Abort does not return
}

}  // namespace lzb::mpi
