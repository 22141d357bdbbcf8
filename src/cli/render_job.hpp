#pragma once
// Which frames a `lzb render` run renders (--frame-range, --resume) and the record it keeps in
// --out for them (frame_record.hpp). Root rank only.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "src/cli/render_command.hpp"

namespace lzb {

struct FramesToRender {
  std::vector<int> frames;  // ascending
  int skipped = 0;          // frames of the range already complete (--resume)
  bool sameJob = false;     // --out holds a record of this job: its frames stay in the report
};

// Checks --out's record against this run's report head: a --resume of another job (one whose
// images would differ) is refused with an InputError naming the field. Lists the frames of
// --frame-range to render: with --resume, those without a complete record. Writes nothing.
FramesToRender framesToRender(const RenderArgs& a, const nlohmann::json& head);

// Once --out exists: starts a new record unless it holds this job's, cuts a torn last line off,
// removes temporaries a killed writer left, and writes the head as job.json.
void startRecord(const RenderArgs& a, const nlohmann::json& head, bool sameJob);

// The record's head (job.json in dir); throws InputError naming the file when it is missing or
// not a report head.
nlohmann::json readJobHead(const std::string& dir);
// The latest record of every frame in dir's frames.jsonl, in frame order.
std::vector<nlohmann::json> recordedFrames(const std::string& dir);

}  // namespace lzb
