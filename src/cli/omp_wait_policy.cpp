#include "src/cli/omp_wait_policy.hpp"

#include <unistd.h>

#include <cstdlib>

namespace lzb {

void preferPassiveOmpWait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  setenv("OMP_WAIT_POLICY", "passive", 1);
  // Same process id, so mpirun still sees its rank; on failure go on with the spinning default.
  execv("/proc/self/exe", argv);
}

}  // namespace lzb
