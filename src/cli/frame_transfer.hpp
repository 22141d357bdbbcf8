#pragma once
// Frame-parallel batches (--frame-groups): a group's root sends each finished frame (image,
// report entry and, with --subsamples, its sub-samples) to the root of the whole job, which
// writes every frame.
#include <nlohmann/json.hpp>

#include "mpi/group.hpp"
#include "src/core/framebuffer.hpp"
#include "src/image/reference.hpp"

namespace lzb {

struct FrameResult {
  Framebuffer image;
  ReferenceFrame own;  // sized only with --subsamples
  nlohmann::json entry;
};

void sendFrame(const mpi::Group& world, int to, const FrameResult& frame);
FrameResult receiveFrame(const mpi::Group& world, int from);

}  // namespace lzb
