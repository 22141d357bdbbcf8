#pragma once
// report.json: parameters, per-frame and per-stage times (per rank), counts, peak memory and,
// with a reference, accuracy. Built at the root rank.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

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
  // The distribution the run used (--distribute auto resolved): "replicate" or "data".
  void setDistribution(const std::string& used) { json_["distribution"] = used; }
  void setMethod(const Renderer& method, const Renderer* reference);
  // Load and set-up wall times, and the method's own set-up figures (mpi::gatherStats).
  void setSetup(double loadSeconds, double setupSeconds, nlohmann::json methodSetup);
  // How accuracy is witnessed: the rule and whose Embree scene it traces (its build is part of
  // setup_seconds when it is its own).
  void setWitness(const WitnessScene& witness);
  void addFrame(int frame, const Camera& camera, nlohmann::json entry, const Framebuffer& image);
  // Wall time of the frame loop (all frames, all frame groups): frames per second.
  void setThroughput(double loopSeconds) { loopSeconds_ = loopSeconds; }
  void setTotal(double seconds);
  void write(const std::filesystem::path& path) const;  // atomically
  void printSummary(std::FILE* out) const;
  const nlohmann::json& json() const { return json_; }

 private:
  nlohmann::json json_;
  double loopSeconds_ = 0.0;
  std::string out_;
};

}  // namespace lzb
