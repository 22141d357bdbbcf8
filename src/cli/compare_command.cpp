#include "src/cli/compare_command.hpp"

#include <cstdio>
#include <string>

#include "raycast/exact/ray_witness.hpp"
#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/image/compare.hpp"
#include "src/scene/load.hpp"

namespace lzb {

void addCompareOptions(CLI::App& c, CompareArgs& a) {
  c.add_option("image", a.test, "EXR written by lzb render (the image to judge)")->required();
  c.add_option("reference", a.reference,
               "EXR of the exact reference, rendered with `lzb render --subsamples`")
      ->required();
  c.add_option("--scene", a.scene,
               "the scene both frames show, as given to lzb render: judge with the ray witness "
               "(a covered pixel whose triangle none of the 17 reference samples sees is correct "
               "when a ray through the pixel sees it first), tracing the camera stored in the "
               "reference EXR's header; gives exactly the figures of `lzb render --reference`. "
               "Without it: the 17-sample rule alone (\"witness\": \"none\"), a lower bound on "
               "sub-pixel geometry (src/image/README.md)");
  c.add_option("--threads,-t", a.threads,
               "threads for the witness's Embree build and rays (0: the cores this rank owns)")
      ->capture_default_str();
}

namespace {

// Accuracy with the ray witness, tracing the reference's camera through the scene loaded here.
nlohmann::json compareWithScene(const CompareArgs& a) {
  const FramePair pair = readFramePair(a.test, a.reference);
  require(pair.origin.has_value(), a.reference,
          "has no camera in its header (lzb.camera.*), which --scene needs: render it again "
          "with this lzb");
  RenderOptions options;
  options.threads = a.threads > 0 ? a.threads : coresOwned();
  useThreads(options.threads);
  const Scene scene = loadScene(a.scene, true);
  require(scene.expandedTriangles() == pair.origin->sceneTriangles, "--scene " + a.scene,
          "has " + std::to_string(scene.expandedTriangles()) + " triangles, but " + a.reference +
              " shows a scene of " + std::to_string(pair.origin->sceneTriangles));
  const WitnessScene witnessScene(scene, nullptr, options);
  const RayWitness witness = witnessScene.witness(pair.origin->camera);
  return compareFrames(pair, &witness);
}

}  // namespace

int runCompare(const CompareArgs& a, const mpi::Group& g) {
  require(a.threads >= 0 && a.threads <= 1024, "--threads", "must be in [0, 1024]");
  const nlohmann::json result = a.scene.empty() ? compareFiles(a.test, a.reference)
                                                : compareWithScene(a);
  if (g.root()) std::printf("%s\n", result.dump(2).c_str());
  return 0;
}

}  // namespace lzb
