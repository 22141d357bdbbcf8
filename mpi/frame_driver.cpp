#include "mpi/frame_driver.hpp"

#include <algorithm>

#include "mpi/composite.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"

namespace lzb::mpi {

namespace {

nlohmann::json rankEntry(int rank, const FrameStats& stats, const CompositeStats& composite) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, seconds] : stats.stageSeconds) stages[name] = seconds;
  stages["composite"] = composite.seconds;
  return {{"rank", rank},
          {"stages", stages},
          {"counts", stats.counts},
          {"bytes_sent", composite.bytesSent},
          {"peak_memory_bytes", peakMemoryBytes()}};
}

// Adds b's numbers into a (keys missing from a are taken over).
void sumInto(nlohmann::json& a, const nlohmann::json& b) {
  for (auto it = b.begin(); it != b.end(); ++it) {
    if (!a.contains(it.key())) a[it.key()] = it.value();
    else if (it.value().is_number() && a[it.key()].is_number())
      a[it.key()] = a[it.key()].get<double>() + it.value().get<double>();
  }
}

}  // namespace

nlohmann::json renderFrame(const Group& g, Renderer& renderer, const Camera& camera, int frame,
                           Framebuffer& fb) {
  g.barrier();  // frame time starts when every rank is ready
  Stopwatch clock;
  fb.resize(camera.width(), camera.height());
  FrameStats stats;
  renderer.render(camera, frame, WorkShare{g.rank, g.size}, fb, stats);
  const CompositeStats composite = compositeAtRoot(g, fb);
  const double seconds = clock.seconds();

  const std::vector<std::string> entries = gatherStrings(g, rankEntry(g.rank, stats, composite).dump());
  if (!g.root()) return nullptr;
  nlohmann::json out = {{"seconds", seconds}, {"stages", nlohmann::json::object()},
                        {"counts", nlohmann::json::object()}, {"ranks", nlohmann::json::array()}};
  double bytes = 0.0, peak = 0.0;
  for (const std::string& text : entries) {
    nlohmann::json e = nlohmann::json::parse(text);
    for (auto it = e["stages"].begin(); it != e["stages"].end(); ++it)
      out["stages"][it.key()] = std::max(out["stages"].value(it.key(), 0.0), it.value().get<double>());
    sumInto(out["counts"], e["counts"]);
    bytes += e["bytes_sent"].get<double>();
    peak = std::max(peak, e["peak_memory_bytes"].get<double>());
    out["ranks"].push_back(std::move(e));
  }
  out["bytes_sent"] = bytes;
  out["peak_memory_bytes"] = peak;
  return out;
}

}  // namespace lzb::mpi
