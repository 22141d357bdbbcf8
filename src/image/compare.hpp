#pragma once
// The core of `lzb compare`: accuracy of one frame file against a reference frame file.
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "src/image/frame_io.hpp"
#include "src/image/witness.hpp"

namespace lzb {

// A frame and its reference, read and checked against each other, ready to compare.
struct FramePair {
  std::filesystem::path testPath, referencePath;
  Framebuffer test;
  ReferenceFrame reference;
  std::optional<FrameOrigin> origin;  // the reference's header (its camera), when it has one
};

// Reads the frame `test` and the reference frame `reference` (an EXR with the sub-sample
// channels: `lzb render --subsamples`). Throws InputError naming the file(s) on a bad file, a
// reference without the sub-sample channels, frames of different sizes, or frames whose headers
// both name a camera and scene and disagree.
FramePair readFramePair(const std::filesystem::path& test, const std::filesystem::path& reference);

// toJson(compare(...)) of the pair (metrics.hpp); `witness` must be made for the reference's
// camera (pair.origin).
nlohmann::json compareFrames(const FramePair& pair, const VisibilityWitness* witness = nullptr);

// compareFrames(readFramePair(test, reference)): the 17-sample rule, no witness.
nlohmann::json compareFiles(const std::filesystem::path& test,
                            const std::filesystem::path& reference);

// True when both origins name the same camera (spec and size, exactly) and the same scene size.
bool sameOrigin(const FrameOrigin& a, const FrameOrigin& b);

}  // namespace lzb
