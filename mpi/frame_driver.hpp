#pragma once
// Renders one frame on every rank (each its WorkShare), composites at the root, and gathers the
// per-rank measurements into the frame's report entry.
#include <nlohmann/json.hpp>

#include "mpi/composite.hpp"
#include "mpi/group.hpp"
#include "src/core/renderer.hpp"

namespace lzb::mpi {

// Every rank calls render(). Each rank shades the tiles it touched (mpi/frame_tiles.hpp: the
// renderer's record, else found from the depths) and sends them with their colour to the root
// (`tiles`, the default); with the other strategies the ranks' depth and ID are composited at the
// root (mpi/composite.hpp), which then shades the whole frame from the IDs. A renderer whose colour
// is not a function of the IDs composites whole pixels instead. fb is either new or the one the
// previous call rendered, unchanged since: then only the tiles that frame left in use are cleared
// (Framebuffer::tilesInUse), so a sparse frame costs what it covers. On return the root's fb holds
// the final image and the returned JSON holds: seconds (wall time of the frame at the root,
// compositing and shading included), stages (each the maximum over ranks, plus "clear" (the frame
// buffer's), "wait" (idle until the slowest rank is done: its maximum is the imbalance),
// "touched" (finding the touched tiles), "composite" (the exchange) and "shade"), counts (each
// rank's share summed over ranks, and the root's shared figures), peak_memory_bytes (maximum over
// ranks), bytes_sent, and ranks[] with every rank's own stages and counts. Elsewhere: null.
class FrameDriver {
 public:
  FrameDriver(const Group& g, const Scene& scene, CompositeStrategy strategy)
      : g_(g), scene_(scene), strategy_(strategy) {}
  nlohmann::json render(Renderer& renderer, const Camera& camera, int frame, Framebuffer& fb) const;
  const Group& group() const { return g_; }

 private:
  const Group& g_;
  const Scene& scene_;
  CompositeStrategy strategy_;
};

// The same gathering for stats outside a frame (a renderer's set-up): stages (maximum over
// ranks), counts (summed, with the root's shared figures) and ranks[]. Null except at the root.
nlohmann::json gatherStats(const Group& g, const FrameStats& stats);

}  // namespace lzb::mpi
