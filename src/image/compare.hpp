#pragma once
// The core of `lzb compare`: accuracy of one frame file against a reference frame file.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace lzb {

// Reads two EXRs written by writeFrame and returns toJson(compare(test, reference)) (see
// metrics.hpp). Throws InputError naming the file(s) on a bad file or a size mismatch.
nlohmann::json compareFiles(const std::filesystem::path& test,
                            const std::filesystem::path& reference);

}  // namespace lzb
