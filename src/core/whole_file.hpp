#pragma once
// A file's whole content as bytes, for the readers that check or parse a file at once.
#include <filesystem>
#include <string>

namespace lzb {

// Throws InputError("<path>: <unreadable>") when the file cannot be opened.
std::string readWholeFile(const std::filesystem::path& path,
                          const std::string& unreadable = "cannot be opened");

}  // namespace lzb
