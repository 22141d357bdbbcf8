#pragma once
// Writes a file under a temporary name and renames it into place, so a crash never leaves a
// truncated output.
#include <filesystem>
#include <functional>
#include <string>

namespace lzb {

// Calls write(tmpPath) and renames tmpPath to path; removes tmpPath and rethrows on failure.
// The temporary keeps path's extension so writers that choose a format by extension still work.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path&)>& write);
void writeTextAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace lzb
