#pragma once
// The steps `lzb render` and `lzb sweep` share before the first frame: checking the render
// options, the output folder, and loading the scene with the image size and camera path.
#include <cstdint>
#include <string>

#include "mpi/group.hpp"
#include "src/cli/render_command.hpp"
#include "src/core/camera.hpp"
#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"
#include "src/core/scene_outline.hpp"
#include "src/regions/share.hpp"

namespace lzb {

// Checks what needs no scene (the method's own options included, through its validate());
// throws InputError naming the option.
void validateRenderArgs(const RenderArgs& a);

// Bytes one frame's reduced reference (a ReferenceFrame) holds.
uint64_t referenceFrameBytes(int width, int height);

// --out must name an existing writable folder or one that can be created; checked before any
// work and without creating anything, so bad input leaves nothing behind.
void checkOutput(const std::string& out);
// Creates --out (and its parents); throws InputError naming it. True when --out was not there.
bool createOutput(const std::string& out);

// The loaded scene and what every frame of a run shares.
struct RenderPlan {
  // Loaded, or standing for a method's stored outline (storedOutline()) or, under --distribute
  // data, for the whole scene of which `held` is this rank's part.
  Scene scene;
  SceneOutline outline;  // what the report says of the scene
  bool sceneLoaded = true;
  RenderOptions options;
  int width = 0, height = 0;
  int frames = 1;
  CameraSpec base;
  double loadSeconds = 0.0;
  regions::HeldShare
      held;  // --distribute data: this rank's part (renderers keep a reference to it)
  // The camera of frame f along the path of `frames` (scene keyframes, else a circle).
  Camera camera(int f) const;
};

// Loads a.scene into `plan` (in place: renderers keep a reference to the scene) unless the method
// holds the scene itself and no --reference needs it (the method's outline then stands for it);
// under --distribute data, only this rank's part of the scene, the regions dealt over `group`
// (its frame group; collective there): a binary PLY of triangles read in slices by the group's
// ranks (src/regions/sliced_share.hpp), PLY, OFF, OBJ and builtin:landscape streamed, never held
// whole; the other scenes loaded whole and cut. Refuses a scene or share whose estimated peak
// (memory_estimate.hpp) this rank cannot hold, before it holds it where it can. Resolves the
// threads (useThreads), image size, clip planes and fov; checks the first camera, the sub-sample
// size and the frame memory. Throws InputError. distribution: kReplicate or kData (auto resolved
// by the caller; kData needs `group`).
void loadPlan(const RenderArgs& a, bool talk, RenderPlan& plan, const mpi::Group* group = nullptr,
              regions::Distribution distribution = regions::Distribution::kReplicate);

// --distribute auto on this rank: whether the whole scene fits replicated. Only a PLY read in
// slices (its header read) or a streamed scene (PLY, OFF, OBJ, builtin:landscape; read once) is
// known before it is loaded; the others are read whole in either mode, and fit as far as auto can
// tell.
bool replicaFits(const RenderArgs& a);

}  // namespace lzb
