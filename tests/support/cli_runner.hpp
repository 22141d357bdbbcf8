#pragma once
// The program's tests: run the lzb program and read what it wrote.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace lzb::test {

struct RunResult {
  int status = -1;     // exit status
  std::string output;  // stdout and stderr together
};

// Runs `lzb ARGS` through the shell; ARGS is pasted as is (quote what needs quoting), after
// `shellPrefix` (e.g. "ulimit -v 3000000; ").
RunResult runLzb(const std::string& args, const std::string& shellPrefix = "");
// The shell prefix that runs lzb on `ranks` MPI ranks (oversubscribed), under `timeout` when it
// is above 0, allowed as root, with an Open MPI session folder of this test process's own
// (CMakeLists.txt, lzb_mpi_tests, says why).
std::string mpiexecPrefix(int ranks, int timeoutSeconds = 0);
// The lzb program the tests run.
std::filesystem::path lzbBinary();
// The test program's work folder: next to its executable, NAME_out.
std::filesystem::path workDir();
// A fresh, empty folder under the test work dir.
std::filesystem::path freshDir(const std::string& name);
nlohmann::json readJson(const std::filesystem::path& file);

}  // namespace lzb::test
