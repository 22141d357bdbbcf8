#pragma once
// What `lzb render --reference` and `lzb sweep` judge frames against: an exact method rendered at
// the pixel centres and at 4x4 sub-samples per pixel (src/image/reference.hpp), and at the root
// the ray witness (raycast/exact/ray_witness.hpp); under --distribute data, the exact method on
// each rank's parts and the witness over the ranks (part_witness.hpp).
#include <memory>
#include <string>

#include "mpi/frame_driver.hpp"
#include "raycast/exact/ray_witness.hpp"
#include "src/core/renderer.hpp"
#include "src/image/metrics.hpp"
#include "src/image/reference.hpp"
#include "src/regions/part_witness.hpp"

namespace lzb {

struct Judge {
  std::unique_ptr<Renderer> reference;
  std::unique_ptr<WitnessScene> witness;        // the root's only: it alone compares
  std::unique_ptr<regions::PartWitness> parts;  // --distribute data: every rank's, for its parts
};

// The exact method `name` (checked by the caller) as a renderer and, where `root`, the witness's
// Embree scene (built here unless the raycast reference lends its own).
Judge makeJudge(const std::string& name, const Scene& scene, const RenderOptions& options,
                bool root);
// The same under --distribute data: the exact method on each of the rank's parts, composited as
// the parts of any method are, and the witness scenes of its parts.
Judge makePartJudge(const std::string& name, const regions::HeldShare& held,
                    const RenderOptions& options);

// Renders `exact` at the 4x4 sub-samples of `camera` (every rank its share) and reduces them with
// its centre render `centres` at the root; elsewhere returns an empty frame. The 4W x 4H image
// (16 bytes per sub-sample) is freed on return.
ReferenceFrame renderSubsamples(const mpi::FrameDriver& driver, Renderer& exact,
                                const Camera& camera, int f, const Framebuffer& centres,
                                double& seconds);

// The reference of one frame at the driver's root (empty elsewhere) and its render times there.
struct ExactFrame {
  ReferenceFrame samples;
  double centreSeconds = 0.0, subsampleSeconds = 0.0;
};
ExactFrame renderReference(const mpi::FrameDriver& driver, const Judge& judge, const Camera& camera,
                           int f);

// At the root: the accuracy of `image` against `exact`, witnessed by rays through `camera`;
// `seconds` receives the time judging took.
Accuracy judgeFrame(const Judge& judge, const Camera& camera, const Framebuffer& image,
                    const ReferenceFrame& exact, double& seconds);
// The same with judge.parts, collective over `group` (the pixels to witness asked at its root,
// answered by every rank); at the root, `raysPerRank` receives the witness rays each rank made.
Accuracy judgePartFrame(const Judge& judge, const mpi::Group& group, const Camera& camera,
                        const Framebuffer& image, const ReferenceFrame& exact, double& seconds,
                        std::vector<uint64_t>& raysPerRank);

}  // namespace lzb
