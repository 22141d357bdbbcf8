#pragma once
// Renders one frame on every rank (each its WorkShare), composites at the root, and gathers the
// per-rank measurements into the frame's report entry.
#include <nlohmann/json.hpp>

#include "mpi/group.hpp"
#include "src/core/renderer.hpp"

namespace lzb::mpi {

// Every rank calls this. On return the root's fb holds the final image and the returned JSON
// holds: seconds (wall time of the frame at the root, compositing included), stages (each the
// maximum over ranks, plus "composite"), counts (each rank's share summed over ranks, and the
// root's shared figures), peak_memory_bytes (maximum over ranks), bytes_sent, and ranks[] with
// every rank's own stages and counts. Elsewhere: null.
nlohmann::json renderFrame(const Group& g, Renderer& renderer, const Camera& camera, int frame,
                           Framebuffer& fb);

// The same gathering for stats outside a frame (a renderer's set-up): stages (maximum over
// ranks), counts (summed, with the root's shared figures) and ranks[]. Null except at the root.
nlohmann::json gatherStats(const Group& g, const FrameStats& stats);

}  // namespace lzb::mpi
