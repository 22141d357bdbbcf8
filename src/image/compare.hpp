#pragma once
// The core of `lzb compare`: accuracy of one frame file against a reference frame file.
#include <filesystem>
#include <nlohmann/json.hpp>

namespace lzb {

// Reads the frame `test` and the reference frame `reference` (an EXR with the sub-sample
// channels: `lzb render --subsamples`) and returns toJson(compare(test, reference)) (see
// metrics.hpp). Throws InputError naming the file(s) on a bad file, a reference without the
// sub-sample channels, or a size mismatch.
nlohmann::json compareFiles(const std::filesystem::path& test,
                            const std::filesystem::path& reference);

}  // namespace lzb
