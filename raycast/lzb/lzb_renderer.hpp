#pragma once
// --method lzb: local z-buffering (Han & Zeiger, sections II-III; see raycast/lzb/README.md).
//
// Per frame: (1) hierarchical frustum culling of the octrees; (2) the partition plane z_clip;
// (3) the near scene (culled leaves in front of the plane) by z-buffer clipped at z_clip: the
// native z-buffer (--near-render native) or OSMesa (gl); (4) the unfinished pixels (left empty
// by the near pass); (5) the far scene by the chosen stage: naive Embree rays (combined with the
// near pass by compositeNearer), or PVL finding by the own octree walk (lazy / selective / OOR /
// final) and the PVL z-buffered on top of the near pass (near scene first, so on an exact depth
// tie between two triangles the near one stays): by the native sparse z-buffer at the unfinished
// pixels (--pvl-render native), or by OSMesa (gl: unclipped into the near pass's GL z-buffer, or
// a pass of its own composited by (depth, ID) after a native near pass); colour comes from the
// IDs after compositing (the frame driver).
//
// Ranks: every rank culls and places the plane alike; ranks rendering at once (the frame driver)
// split the native near pass by triangle ranges and OR their covered pixels, so every rank knows
// the unfinished pixels and keeps the same plane state (a GL near pass, and shares rendered one
// after another, draw the whole near scene on every rank); each casts rays only in its screen
// tiles (tile % size == rank) and draws only its PVL part; compositing all ranks' framebuffers
// by (depth, id) gives the 1-rank image.
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "raycast/exact/embree_scene.hpp"
#include "raycast/lzb/lzb_accel.hpp"
#include "raycast/lzb/lzb_cull.hpp"
#include "raycast/lzb/lzb_draw_lists.hpp"
#include "raycast/lzb/lzb_hit_leaves.hpp"
#include "raycast/lzb/lzb_oor.hpp"
#include "raycast/lzb/lzb_options.hpp"
#include "raycast/lzb/lzb_plane.hpp"
#include "src/zbuffer/native_raster.hpp"
#include "raycast/lzb/lzb_ray_walk.hpp"
#include "raycast/lzb/lzb_tile_cast.hpp"
#include "src/core/renderer.hpp"
#include "src/zbuffer/triangle_rasterizer.hpp"

namespace lzb::localz {

class LzbRenderer : public Renderer {
 public:
  // Builds the octrees (Octree-o, ropes), the Embree scene and the GL context. Throws InputError
  // for out-of-range options.
  LzbRenderer(const Scene& scene, const RenderOptions& options, const LzbOptions& lzb);
  ~LzbRenderer() override;

  std::string name() const override { return "lzb"; }
  std::string decomposition() const override;
  // How the ranks share the near pass, for decomposition() texts.
  std::string nearPassText() const;
  // The stages below in order, each timed.
  void render(const Camera& camera, int frame, const WorkShare& share, Framebuffer& fb,
              FrameStats& stats) override;
  FrameStats setupStats() const override;

  // One frame's state as it passes through the stages.
  struct Frame {
    const Camera* camera = nullptr;
    WorkShare share;
    double zClip = 0.0;              // the partition plane (view depth)
    DrawLists nearLists;             // the near scene
    uint64_t nearDrawn = 0;          // its triangles this rank drew
    bool nearSplit = false;          // the ranks drew parts of it at once (WorkShare::orWords)
    uint64_t farTriangles = 0;       // triangle entries of culled leaves reaching beyond zClip
    bool glPassOpen = false;         // the near pass's GL z-buffer awaits the PVL
    uint64_t unfinished = 0;         // pixels the near pass (of every rank) left empty
    std::vector<int> tiles;          // this rank's screen tiles (dealt by castFarRays)
    const OorObjects* oor = nullptr; // the OOR objects (oor and final stages)
    TileCastCounts tileCounts;
    bool farApart = false;     // farPass_ holds far-scene pixels still to composite with fb
    bool nativePvl = false;    // the native z-buffer drew the PVL
    // Set by a composing method (hybrid): what another pass draws, which the cull leaves out
    // (whole placed nodes) and the walk skips (so the far rays walk whatever --lzb-rays says).
    const LeafFilter* leafFilter = nullptr;
    bool walked = false;  // the far rays were the octree walk's (else Embree's)
    // Set by a composing method (hybrid) before the plane: the far pass is each unfinished
    // pixel's Embree hit (the naive stage's rays), with no PVL, whatever --lzb-stage says.
    bool directRays = false;
    std::optional<CoarseHits> coarse;  // the plane's coarse rays, when cast before it
  };
  // 1. Hierarchical view-frustum culling of the octrees (up to view depth farDepth when it is
  // nearer than the camera's far plane: a composing method's partial cull; with a triangle
  // budget, a probe's, which may stop once that many are listed: cullScene).
  void cull(Frame& f, double farDepth = std::numeric_limits<double>::infinity(),
            uint64_t triangleBudget = std::numeric_limits<uint64_t>::max());
  // The median view depth of the plane's coarse rays' hits (camera far without any hit); the
  // rays are cast unless f.coarse holds them already, and kept there for the plane.
  double medianCoarseHit(Frame& f) const;
  // 2. The partition plane z_clip.
  void placePlane(Frame& f);
  // 3. The near scene by z-buffer, clipped at the plane, straight into fb.
  void drawNearPass(Frame& f, Framebuffer& fb);
  // 4. The unfinished pixels (left empty by the near pass of every rank).
  void markUnfinished(Frame& f, const Framebuffer& fb);
  // 5a. OOR objects: projected content boxes of the far leaves (oor and final stages).
  void projectFarObjects(Frame& f);
  // 5b. The far scene from the unfinished pixels of this rank's tiles: naive Embree rays into
  // farPass_, or PVL finding by Embree (the leaves around each hit) or by the octree walk.
  void castFarRays(Frame& f);
  // 6. The PVL by z-buffer on top of the near pass.
  void renderPvl(Frame& f, Framebuffer& fb);
  // Whether this frame's far pass is direct Embree hits (the naive stage, or Frame::directRays).
  bool directRays(const Frame& f) const { return !lzb_.usesPvl() || f.directRays; }
  // 7. A far pass drawn apart (naive rays, a GL PVL after a native near pass) joins fb by the
  // compositing key.
  void combine(Frame& f, Framebuffer& fb);
  // The frame's counts: shared figures (plane, cull, near pass) and this rank's share (rays,
  // walk, PVL).
  void countFrame(const Frame& f, FrameStats& stats) const;

  // What the last frame did, for tests and studies.
  struct FrameDetail {
    PlaneDecision plane;
    Framebuffer nearPass;  // ids/depths of this rank's near pass alone (keepNearPass)
    std::vector<uint32_t> castPixels;  // framebuffer indices of the pixels rays were cast from
    DrawLists pvl;                     // this rank's PVL (empty for naive)
    RayWalkCounts walk;                // --lzb-rays walk
    HitLeafCounts hitLeaves;           // --lzb-rays embree
  };
  const FrameDetail& lastFrame() const { return last_; }
  // Keep a copy of each frame's near pass in lastFrame().nearPass (off: the near pass is drawn
  // straight into the frame, nothing copied).
  void keepNearPass(bool keep) { keepNearPass_ = keep; }
  const LzbAccel& accel() const { return *accel_; }
  const EmbreeScene& embree() const { return *embree_; }
  const CulledScene& culled() const { return culled_; }
  // The unfinished pixels of the last near pass (1), per pixel.
  const std::vector<uint8_t>& unfinishedMask() const { return open_; }
  const LzbOptions& options() const { return lzb_; }

 private:
  void measureDepthComplexity(const Camera& camera, FrameStats& stats);
  // After a split near pass: ORs the ranks' covered pixels, closes in open_ those another rank
  // covered and returns their number.
  uint64_t closeCoveredElsewhere(const WorkShare& share);
  // castFarRays by engine, each filling tilePixels (per owned tile: the pixels cast).
  // Runs castTile(thread, rect, tile, k, scratch, counts, cast pixels) on this rank's k-th
  // owned tile, over the frame's threads, and sums the tiles' counts into f.tileCounts.
  // This frame's tiles of this rank (--tile-deal): interleaved, or contiguous runs of equal ray
  // count.
  std::vector<int> dealTiles(const Frame& f, const TileCastInput& input) const;
  template <typename CastTile>
  void forOwnedTiles(Frame& f, std::vector<std::vector<uint32_t>>& tilePixels, CastTile castTile);
  void castNaiveRays(Frame& f, const TileCastInput& input,
                     std::vector<std::vector<uint32_t>>& tilePixels);
  void findPvlByWalk(Frame& f, const TileCastInput& input,
                     std::vector<std::vector<uint32_t>>& tilePixels);
  void findPvlByEmbree(Frame& f, const TileCastInput& input,
                       std::vector<std::vector<uint32_t>>& tilePixels);

  const Scene& scene_;
  RenderOptions options_;
  LzbOptions lzb_;
  std::unique_ptr<LzbAccel> accel_;
  std::unique_ptr<EmbreeScene> embree_;
  std::unique_ptr<TriangleRasterizer> raster_;
  PartitionPlane plane_;
  std::vector<RayWalker> walkers_;          // one per thread (--lzb-rays walk)
  std::vector<HitLeafRecorder> recorders_;  // one per thread (--lzb-rays embree)
  // Per-frame state kept between frames so its memory is reused (no page faults per frame).
  std::vector<PvlPart> parts_;  // one per owned tile
  CulledScene culled_;
  std::unique_ptr<OorObjects> oor_;
  NativeRasterizer native_;    // --near-render / --pvl-render native
  std::vector<LeafLoad> loads_;  // the cost plane's, per culled leaf
  std::vector<uint8_t> open_;  // the near pass's unfinished pixels (1), per pixel
  std::vector<uint64_t> mine_, covered_;  // covered pixels, 64 a word: this rank's, every rank's
  Framebuffer farPass_;
  FrameDetail last_;
  bool keepNearPass_ = false;
};

}  // namespace lzb::localz
