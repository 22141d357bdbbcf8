#pragma once
// report.json: parameters, per-frame and per-stage times (per rank), counts, peak memory and,
// with a reference, accuracy. Built at the root rank: the head as the run sets up, the frames from
// the job's record (frame_record.hpp), so a resumed run and `lzb report` give every frame.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mpi/group.hpp"
#include "raycast/exact/ray_witness.hpp"
#include "src/cli/render_command.hpp"
#include "src/core/renderer.hpp"
#include "src/core/scene_outline.hpp"

namespace lzb {

nlohmann::json sceneSummary(const SceneOutline& scene);

class Report {
 public:
  Report(const RenderArgs& args, const RenderOptions& options, const mpi::Group& g,
         const SceneOutline& scene, bool sceneLoaded, const std::string& commandLine);
  // A report of a record's head (job.json) whose images are in `out`.
  Report(nlohmann::json head, std::string out) : json_(std::move(head)), out_(std::move(out)) {}
  void setImageSize(int width, int height);
  // The distribution the run used (--distribute auto resolved): "replicate" or "data".
  void setDistribution(const std::string& used) { json_["distribution"] = used; }
  void setMethod(const Renderer& method, const Renderer* reference);
  // Load and set-up wall times, and the method's own set-up figures (mpi::gatherStats).
  void setSetup(double loadSeconds, double setupSeconds, nlohmann::json methodSetup);
  // How accuracy is witnessed: the ray witness, whether it traces the raycast reference's own
  // Embree scenes, else the time this rank took to build its own (part of setup_seconds).
  void setWitness(bool sharedWithReference, double buildSeconds);
  // Frame f's entry completed with its frame number, covered pixels, triangles and camera.
  nlohmann::json frameEntry(int frame, const Camera& camera, nlohmann::json entry,
                            const Framebuffer& image) const;
  // Everything but the frames and the summary: what job.json keeps.
  nlohmann::json head() const;
  // The report's frames: every frame of the job's record (latestPerFrame).
  void setFrames(std::vector<nlohmann::json> frames);
  // Wall time of this run's frame loop (all frame groups) and the frames it rendered.
  void setThroughput(double loopSeconds, size_t framesRendered);
  // The summary over the frames; totalSeconds < 0: not a run (`lzb report`), no run figures.
  void setTotal(double totalSeconds);
  void write(const std::filesystem::path& path) const;  // atomically
  void printSummary(std::FILE* out) const;
  const nlohmann::json& json() const { return json_; }

 private:
  nlohmann::json json_;
  double loopSeconds_ = 0.0;
  size_t framesRendered_ = 0;
  std::string out_;
};

}  // namespace lzb
