#include "src/cli/judge.hpp"

#include "src/cli/methods.hpp"
#include "src/core/timer.hpp"

namespace lzb {

Judge makeJudge(const std::string& name, const Scene& scene, const RenderOptions& options, bool root) {
  Judge judge;
  judge.reference = methodNamed(name, "--reference").create(scene, options);
  // Built once (set-up time), unless the raycast reference lends its Embree scene.
  if (root) judge.witness = std::make_unique<WitnessScene>(scene, judge.reference.get(), options.threads);
  return judge;
}

ReferenceFrame renderSubsamples(const mpi::FrameDriver& driver, Renderer& exact,
                                const Camera& camera, int f, const Framebuffer& centres,
                                double& seconds) {
  Framebuffer fine;
  const nlohmann::json stats = driver.render(exact, subsampleCamera(camera), f, fine);
  if (!driver.group().root()) return {};
  seconds = stats["seconds"].get<double>();
  return reduceReference(centres, fine);
}

ExactFrame renderReference(const mpi::FrameDriver& driver, const Judge& judge, const Camera& camera,
                           int f) {
  ExactFrame exact;
  Framebuffer centres;
  const nlohmann::json stats = driver.render(*judge.reference, camera, f, centres);
  exact.samples = renderSubsamples(driver, *judge.reference, camera, f, centres, exact.subsampleSeconds);
  if (driver.group().root()) exact.centreSeconds = stats["seconds"].get<double>();
  return exact;
}

Accuracy judgeFrame(const Judge& judge, const Camera& camera, const Framebuffer& image,
                    const ReferenceFrame& exact, double& seconds) {
  Stopwatch clock;
  const RayWitness witness = judge.witness->witness(camera);
  const Accuracy accuracy = compare(image, exact, &witness);
  seconds = clock.seconds();
  return accuracy;
}

}  // namespace lzb
