#include "tests/support/cli_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>

namespace lzb::test {

RunResult runLzb(const std::string& args, const std::string& shellPrefix) {
  RunResult r;
  const std::string cmd = shellPrefix + lzbBinary().string() + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

std::string mpiexecPrefix(int ranks, int timeoutSeconds) {
  const std::filesystem::path sessions = workDir() / "mpi-sessions" / std::to_string(getpid());
  // Ranks of one machine: shared memory (ob1), no UCX probe (CMakeLists.txt, lzb_mpi_tests).
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_pml=ob1 "
         "OMPI_MCA_osc=^ucx OMPI_MCA_orte_tmpdir_base=" +
         sessions.string() + " " +
         (timeoutSeconds > 0 ? "timeout " + std::to_string(timeoutSeconds) + " " : "") +
         LZB_MPIEXEC + " -n " + std::to_string(ranks) + " --oversubscribe ";
}

std::filesystem::path freshDir(const std::string& name) {
  const std::filesystem::path dir = workDir() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

nlohmann::json readJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

std::filesystem::path lzbBinary() {
  return LZB_BINARY;
}

std::filesystem::path workDir() {
  // One library for every test program: each finds its own folder from its executable's path.
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe");
  return exe += "_out";
}

}  // namespace lzb::test
