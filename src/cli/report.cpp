#include "src/cli/report.hpp"

#include <algorithm>
#include <vector>

#include "src/cli/methods.hpp"
#include "src/core/atomic_file.hpp"
#include "src/core/statistics.hpp"
#include "src/core/system.hpp"

namespace lzb {

namespace {

nlohmann::json vec(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

nlohmann::json sceneSummary(const SceneOutline& scene) {
  return {{"source", scene.source},
          {"triangles_unique", scene.uniqueTriangles},
          {"triangles_expanded", scene.expandedTriangles},
          {"nodes", scene.nodes},
          {"instance_depth", scene.instanceDepth},
          {"dropped_degenerate", scene.stats.degenerate},
          {"dropped_nonfinite", scene.stats.nonFinite},
          {"bounds", {{"min", vec(scene.bounds.lo)}, {"max", vec(scene.bounds.hi)}}}};
}

Report::Report(const RenderArgs& a, const RenderOptions& options, const mpi::Group& g,
               const SceneOutline& scene, bool sceneLoaded, const std::string& commandLine)
    : out_(a.out) {
  nlohmann::json summary = sceneSummary(scene);
  summary["loaded"] = sceneLoaded;  // false: rendered from the method's store, the scene unread
  json_ = {
      {"lzb_version", "0.1"},
      {"command", commandLine},
      {"scene", summary},
      {"method", a.method},
      {"method_exact", methodNamed(a.method, "--method").exact()},
      {"parameters",
       {{"seed", a.seed},
        {"quality", a.quality.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.quality)},
        {"frames", a.frames},
        {"composite", a.composite},
        {"frame_groups", a.frameGroups},
        {"distribute", a.distribute},
        {"bvh", a.bvh},
        {"regions", a.regions},
        {"frame_range", a.frameRange},
        {"resume", a.resume},
        {"reference", a.reference.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.reference)},
        {"subsamples", a.subsamples},
        {"fov", a.fov},
        {"near", a.nearPlane},
        {"far", a.farPlane}}},
      {"method_parameters", methodNamed(a.method, "--method").parameters()},
      {"ranks", g.size},
      {"threads", options.threads},
      {"frames", nlohmann::json::array()}};
}

void Report::setMethod(const Renderer& method, const Renderer* reference) {
  json_["decomposition"] = method.decomposition();
  if (reference) json_["reference_decomposition"] = reference->decomposition();
}

void Report::setSetup(double loadSeconds, double setupSeconds, nlohmann::json methodSetup) {
  json_["load_seconds"] = loadSeconds;
  json_["setup_seconds"] = setupSeconds;
  json_["setup"] = std::move(methodSetup);
}

void Report::setWitness(bool sharedWithReference, double buildSeconds) {
  json_["witness"] = {
      {"rule", RayWitness::kName},
      {"embree_scene", sharedWithReference ? "the raycast reference's" : "built for the witness"},
      {"build_seconds", buildSeconds}};
}

void Report::setImageSize(int width, int height) {
  json_["width"] = width;
  json_["height"] = height;
}

nlohmann::json Report::frameEntry(int frame, const Camera& camera, nlohmann::json entry,
                                  const Framebuffer& image) const {
  entry["frame"] = frame;
  entry["covered_pixels"] = image.coveredCount();
  entry["triangles"] = {{"unique", json_["scene"]["triangles_unique"]},
                        {"expanded", json_["scene"]["triangles_expanded"]}};
  entry["camera"] = {{"position", vec(camera.position())},
                     {"up", vec(camera.spec().up)},
                     {"look_at", vec(camera.spec().lookAt)},
                     {"fov", camera.fovyDegrees()},
                     {"near", camera.nearPlane()},
                     {"far", camera.farPlane()}};
  return entry;
}

nlohmann::json Report::head() const {
  nlohmann::json head = json_;
  head.erase("frames");
  head.erase("summary");
  return head;
}

void Report::setFrames(std::vector<nlohmann::json> frames) {
  json_["frames"] = std::move(frames);
}

void Report::setThroughput(double loopSeconds, size_t framesRendered) {
  loopSeconds_ = loopSeconds;
  framesRendered_ = framesRendered;
}

void Report::setTotal(double totalSeconds) {
  std::vector<double> times;
  double rate = 1.0;
  bool haveAccuracy = false;
  for (const auto& f : json_["frames"]) {
    times.push_back(f["seconds"].get<double>());
    if (f.contains("accuracy")) {
      haveAccuracy = true;
      rate = std::min(rate, f["accuracy"]["correct_rate_covered"].get<double>());
    }
  }
  double mean = 0.0;
  for (double t : times) mean += t / double(times.size());
  json_["summary"] = {{"frames", times.size()},
                      {"mean_frame_seconds", mean},
                      {"median_frame_seconds", times.empty() ? 0.0 : median(times)}};
  if (totalSeconds >= 0.0) {  // this run's own figures
    nlohmann::json& s = json_["summary"];
    s["total_seconds"] = totalSeconds;
    s["frames_rendered"] = framesRendered_;
    s["frame_loop_seconds"] = loopSeconds_;
    s["frames_per_second"] = loopSeconds_ > 0.0 ? double(framesRendered_) / loopSeconds_ : 0.0;
    s["peak_memory_bytes_root"] = peakMemoryBytes();
  }
  if (haveAccuracy) json_["summary"]["min_correct_rate_covered"] = rate;
}

void Report::write(const std::filesystem::path& path) const {
  writeTextAtomically(path, json_.dump(2) + "\n");
}

void Report::printSummary(std::FILE* out) const {
  const auto& s = json_["summary"];
  const auto frames = json_["frames"].size();
  std::fprintf(out, "lzb: %s, method %s, %d rank(s) x %d thread(s), %dx%d\n",
               json_["scene"]["source"].get<std::string>().c_str(),
               json_["method"].get<std::string>().c_str(), json_["ranks"].get<int>(),
               json_["threads"].get<int>(), json_["width"].get<int>(), json_["height"].get<int>());
  std::fprintf(out, "  triangles: %llu unique, %llu expanded\n",
               (unsigned long long)json_["scene"]["triangles_unique"].get<uint64_t>(),
               (unsigned long long)json_["scene"]["triangles_expanded"].get<uint64_t>());
  std::fprintf(out, "  frame time: %.4f s median over %zu frame(s)\n",
               s["median_frame_seconds"].get<double>(), frames);
  if (s.contains("min_correct_rate_covered"))
    std::fprintf(out, "  accuracy vs %s: correct (covered pixels) >= %.5f\n",
                 json_["parameters"]["reference"].get<std::string>().c_str(),
                 s["min_correct_rate_covered"].get<double>());
  const std::string dir = std::filesystem::absolute(out_).string();
  const int first = frames ? json_["frames"][0]["frame"].get<int>() : 0;
  std::fprintf(out, "  images: %s/frame_%04d.png (.exr)%s\n", dir.c_str(), first,
               frames > 1 ? " ..." : "");
  std::fprintf(out, "  report: %s/report.json\n", dir.c_str());
}

}  // namespace lzb
