#include "src/cli/judge.hpp"

#include "src/cli/methods.hpp"
#include "src/core/timer.hpp"
#include "src/regions/part_renderer.hpp"

namespace lzb {

Judge makeJudge(const std::string& name, const Scene& scene, const RenderOptions& options,
                bool root) {
  Judge judge;
  judge.reference = methodNamed(name, "--reference").create(scene, options);
  // Built once (set-up time), unless the raycast reference lends its Embree scene.
  if (root) judge.witness = std::make_unique<WitnessScene>(scene, judge.reference.get(), options);
  return judge;
}

Judge makePartJudge(const std::string& name, const regions::HeldShare& held,
                    const RenderOptions& options) {
  const Method& method = methodNamed(name, "--reference");
  std::vector<std::unique_ptr<Renderer>> inner;
  std::vector<const Renderer*> lent;
  for (const regions::ScenePart& part : held.parts) {
    inner.push_back(part.scene.expandedTriangles() > 0 ? method.create(part.scene, options)
                                                       : nullptr);
    lent.push_back(inner.back().get());
  }
  Judge judge;
  judge.parts = std::make_unique<regions::PartWitness>(held, lent, options);
  judge.reference = regions::makePartRenderer(held, std::move(inner), name);
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
  exact.samples =
      renderSubsamples(driver, *judge.reference, camera, f, centres, exact.subsampleSeconds);
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

Accuracy judgePartFrame(const Judge& judge, const mpi::Group& group, const Camera& camera,
                        const Framebuffer& image, const ReferenceFrame& exact, double& seconds,
                        std::vector<uint64_t>& raysPerRank) {
  Stopwatch clock;
  // First the pixels the 17 samples leave open, then their answers from every rank.
  regions::AskedWitness asked;
  if (group.root()) compare(image, exact, &asked);
  const std::vector<regions::WitnessQuestion> questions = asked.questions();
  std::vector<uint8_t> proven = judge.parts->answer(group, camera, questions, raysPerRank);
  if (!group.root()) return {};
  const regions::AnsweredWitness answered(questions, std::move(proven));
  const Accuracy accuracy = compare(image, exact, &answered);
  seconds = clock.seconds();
  return accuracy;
}

}  // namespace lzb
