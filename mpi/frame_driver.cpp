#include "mpi/frame_driver.hpp"

#include <algorithm>

#include "mpi/collectives.hpp"
#include "mpi/composite.hpp"
#include "mpi/frame_tiles.hpp"
#include "src/core/shading.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"

namespace lzb::mpi {

namespace {

nlohmann::json rankEntry(int rank, const FrameStats& stats) {
  nlohmann::json stages = nlohmann::json::object();
  for (const auto& [name, seconds] : stats.stageSeconds) stages[name] = seconds;
  nlohmann::json entry = {{"rank", rank},
                          {"stages", stages},
                          {"counts", stats.counts},
                          {"shared", stats.shared},
                          {"peak_memory_bytes", peakMemoryBytes()}};
  // The set-up's entry: what the rank's peak cost a triangle it holds.
  const double held = stats.counts.value("held_unique_triangles", 0.0);
  if (held > 0.0) entry["peak_bytes_per_unique_triangle"] = double(peakMemoryBytes()) / held;
  return entry;
}

// Adds b's numbers into a (keys missing from a are taken over).
void sumInto(nlohmann::json& a, const nlohmann::json& b) {
  for (auto it = b.begin(); it != b.end(); ++it) {
    if (!a.contains(it.key())) a[it.key()] = it.value();
    else if (it.value().is_number() && a[it.key()].is_number())
      a[it.key()] = a[it.key()].get<double>() + it.value().get<double>();
  }
}

// Gathers every rank's entry at the root: stages as the maximum over ranks, counts summed, the
// root's shared figures added to the counts (every rank computed them alike), peak memory as the
// maximum.
nlohmann::json gather(const Group& g, const nlohmann::json& mine) {
  const std::vector<std::string> entries = gatherStrings(g, mine.dump());
  if (!g.root()) return nullptr;
  nlohmann::json out = {{"stages", nlohmann::json::object()},
                        {"counts", nlohmann::json::object()},
                        {"ranks", nlohmann::json::array()}};
  double peak = 0.0;
  for (const std::string& text : entries) {
    nlohmann::json e = nlohmann::json::parse(text);
    for (auto it = e["stages"].begin(); it != e["stages"].end(); ++it)
      out["stages"][it.key()] = std::max(out["stages"].value(it.key(), 0.0), it.value().get<double>());
    sumInto(out["counts"], e["counts"]);
    peak = std::max(peak, e["peak_memory_bytes"].get<double>());
    out["ranks"].push_back(std::move(e));
  }
  out["counts"].update(out["ranks"][0]["shared"]);
  for (nlohmann::json& e : out["ranks"]) e.erase("shared");
  out["peak_memory_bytes"] = peak;
  return out;
}

// fb sized for the camera and empty: only the tiles its last frame may have left in use when the
// driver knows them (a sparse frame is cheap to clear), else every pixel.
void clearForFrame(Framebuffer& fb, const Camera& camera) {
  const ScreenTiles tiles(camera.width(), camera.height());
  if (fb.width == camera.width() && fb.height == camera.height() &&
      fb.tilesInUse.size() == size_t(tiles.count()))
    clearTiles(fb, tiles, fb.tilesInUse);
  else
    fb.resize(camera.width(), camera.height());
  fb.tilesInUse.clear();
}

}  // namespace

nlohmann::json gatherStats(const Group& g, const FrameStats& stats) {
  return gather(g, rankEntry(g.rank, stats));
}

nlohmann::json FrameDriver::render(Renderer& renderer, const Camera& camera, int frame,
                                   Framebuffer& fb) const {
  const Group& g = g_;
  g.barrier();  // frame time starts when every rank is ready
  Stopwatch clock;
  FrameStats stats;
  clearForFrame(fb, camera);
  stats.addStage("clear", clock.seconds());
  WorkShare share{g.rank, g.size};
  if (g.size > 1) {
    share.orWords = [&g](std::span<uint64_t> words) {
      LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, words.data(), int(words.size()), MPI_UINT64_T,
                                 MPI_BOR, g.comm));
    };
    share.minDoubles = [&g](std::span<double> values) {
      LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE,
                                 MPI_MIN, g.comm));
    };
    share.sumWords = [&g](std::span<uint64_t> words) {
      LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, words.data(), int(words.size()), MPI_UINT64_T,
                                 MPI_SUM, g.comm));
    };
  }
  renderer.render(camera, frame, share, fb, stats);
  const bool fromIds = renderer.colourFromIds();
  // Each rank shades the tiles it touched, at once, and sends them with their colour (the root
  // alone shading the whole frame after the composite cost more), unless the keys go alone.
  const bool tileComposite = g.size > 1 && strategy_ == CompositeStrategy::kTiles;
  const bool keysAlone = fromIds && g.size > 1 && !tileComposite;
  const ScreenTiles tiles(fb.width, fb.height);
  std::vector<uint8_t> touched;
  if (!keysAlone && (tileComposite || renderer.colourOnlyWhereCovered())) {
    Stopwatch scan;
    touched = takeTouchedTiles(fb, tiles, stats);
    stats.addStage("touched", scan.seconds());
  }
  if (fromIds && !keysAlone) {
    Stopwatch shading;
    shadePixels(scene_, camera, tilePixels(fb, tiles, touched), fb.id, fb.color);
    stats.addStage("shade", shading.seconds());
  }
  if (g.size > 1) {  // idle until the slowest rank is done, so "composite" is the exchange alone
    Stopwatch idle;
    g.barrier();
    stats.addStage("wait", idle.seconds());
  }
  const CompositeStats composite =
      keysAlone ? compositeAtRoot(g, fb, strategy_, scene_.expandedTriangles() > 0xffffffffull)
                : compositeWithColour(g, fb, strategy_, touched,
                                      scene_.expandedTriangles() > 0xffffffffull);
  stats.addStage("composite", composite.seconds);
  if (keysAlone && g.root()) {
    Stopwatch shading;
    shadeFromIds(scene_, camera, fb);
    stats.addStage("shade", shading.seconds());
  }
  // The touched tiles hold the frame's every non-empty pixel (the root's counting those it
  // received) unless the renderer's own colour spreads past them, or another strategy wrote the
  // root's frame.
  if ((g.size == 1 || tileComposite) && renderer.colourOnlyWhereCovered() && !touched.empty())
    fb.tilesInUse = std::move(touched);
  const double seconds = clock.seconds();

  nlohmann::json mine = rankEntry(g.rank, stats);
  mine["bytes_sent"] = composite.bytesSent;
  nlohmann::json out = gather(g, mine);
  if (!g.root()) return nullptr;
  double bytes = 0.0;
  for (const nlohmann::json& e : out["ranks"]) bytes += e["bytes_sent"].get<double>();
  out["seconds"] = seconds;
  out["bytes_sent"] = bytes;
  return out;
}

}  // namespace lzb::mpi
