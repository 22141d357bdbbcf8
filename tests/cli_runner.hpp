#pragma once
// Runs the lzb program from tests and reads what it wrote.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace lzb::test {

struct RunResult {
  int status = -1;     // exit status
  std::string output;  // stdout and stderr together
};

// Runs `lzb ARGS` through the shell; ARGS is pasted as is (quote what needs quoting), after
// `shellPrefix` (e.g. "ulimit -v 3000000; ").
RunResult runLzb(const std::string& args, const std::string& shellPrefix = "");
// A fresh, empty folder under the test work dir.
std::filesystem::path freshDir(const std::string& name);
nlohmann::json readJson(const std::filesystem::path& file);
std::filesystem::path dataDir();

}  // namespace lzb::test
