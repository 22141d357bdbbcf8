#include "src/cli/render_job.hpp"

#include <filesystem>
#include <fstream>
#include <set>

#include "src/cli/frame_record.hpp"
#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"

namespace lzb {

namespace fs = std::filesystem;

namespace {

// This job's head recorded in `dir`, or null when dir holds no record.
nlohmann::json recordedHead(const std::string& dir) {
  std::error_code ec;
  return fs::exists(fs::path(dir) / kJobFile, ec) ? readJobHead(dir) : nlohmann::json();
}

// The frames of the range whose record and files are complete in dir.
std::set<int> completeFrames(const std::string& dir, FrameRange range) {
  std::set<int> done;
  for (const nlohmann::json& record : recordedFrames(dir)) {
    const int f = record.at("frame").get<int>();
    if (f >= range.begin && f < range.end && frameComplete(dir, record)) done.insert(f);
  }
  return done;
}

}  // namespace

FramesToRender framesToRender(const RenderArgs& a, const nlohmann::json& head) {
  FramesToRender plan;
  const nlohmann::json recorded = recordedHead(a.out);
  if (!recorded.is_null()) {
    const std::string difference = keyDifference(imageKey(recorded), imageKey(head));
    require(!a.resume || difference.empty(), "--resume",
            (fs::path(a.out) / kJobFile).string() + " records another job (" + difference + ")");
    plan.sameJob = difference.empty();
  }
  const FrameRange range = parseFrameRange(a.frameRange, a.frames, "--frame-range");
  const std::set<int> done =
      a.resume && plan.sameJob ? completeFrames(a.out, range) : std::set<int>();
  for (int f = range.begin; f < range.end; ++f)
    if (!done.count(f)) plan.frames.push_back(f);
  plan.skipped = int(done.size());
  return plan;
}

void startRecord(const RenderArgs& a, const nlohmann::json& head, bool sameJob) {
  const fs::path frames = fs::path(a.out) / kFramesFile;
  std::error_code ec;
  if (!sameJob) fs::remove(frames, ec);  // another job's record: this run starts a new one
  trimTornLine(frames);
  removeStaleTemporaries(a.out);
  writeTextAtomically(fs::path(a.out) / kJobFile, head.dump(2) + "\n");
}

nlohmann::json readJobHead(const std::string& dir) {
  const fs::path file = fs::path(dir) / kJobFile;
  std::ifstream in(file);
  require(bool(in), file.string(), "cannot read the job's record (is this a `lzb render` --out?)");
  const nlohmann::json head = nlohmann::json::parse(in, nullptr, false);
  try {
    imageKey(head);  // every field a resume compares is there
  } catch (const nlohmann::json::exception&) {
    throw InputError(file.string() + ": not a job record written by `lzb render`");
  }
  return head;
}

std::vector<nlohmann::json> recordedFrames(const std::string& dir) {
  return latestPerFrame(readFrameRecords(fs::path(dir) / kFramesFile));
}

}  // namespace lzb
