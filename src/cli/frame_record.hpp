#pragma once
// A render job's record in --out, kept so a killed job loses nothing and can resume:
//  - job.json: the report's head (scene, method, parameters, ranks, set-up), rewritten by every
//    run into the folder;
//  - frames.jsonl: one line per finished frame (the report's per-frame entry and the sizes of the
//    frame's files), appended by one write once the frame's files are in place. A kill at any
//    instant leaves whole lines and at most one torn last line, which readers leave out.
// report.json is rebuilt from the two (at the end of a run, and by `lzb report DIR`).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lzb {

inline constexpr const char* kJobFile = "job.json";
inline constexpr const char* kFramesFile = "frames.jsonl";

// Frames [begin, end) of a path of --frames frames.
struct FrameRange {
  int begin = 0, end = 0;
};

// "A:B" (frames A..B-1), "A:" (A to the end) or "" (the whole path) against a path of `frames`;
// throws InputError naming `field` unless 0 <= A < B <= frames.
FrameRange parseFrameRange(const std::string& text, int frames, const std::string& field);

// The whole lines of a frames.jsonl (none when it does not exist). A torn last line (no newline,
// or not a JSON object) is left out; a bad line before the last throws InputError `file:line`.
std::vector<nlohmann::json> readFrameRecords(const std::filesystem::path& file);

// Cuts a torn last line off, so the next record starts a line of its own.
void trimTornLine(const std::filesystem::path& file);

// Appends records to a frames.jsonl, each as one write(2) of one whole line.
class FrameRecordWriter {
 public:
  explicit FrameRecordWriter(const std::filesystem::path& file);
  ~FrameRecordWriter();
  FrameRecordWriter(const FrameRecordWriter&) = delete;
  FrameRecordWriter& operator=(const FrameRecordWriter&) = delete;
  void append(const nlohmann::json& record);

 private:
  std::string path_;
  int fd_ = -1;
};

// The fields of a report head that decide a job's images and records: scene, method and its
// parameters, seed, path, size, clip planes, reference, sub-samples and, for approximate methods,
// the distribution and its regions. Not ranks, threads, composite or frame groups.
nlohmann::json imageKey(const nlohmann::json& head);
// Empty when the keys are equal, else "FIELD: was A, now B" for the first field that differs.
std::string keyDifference(const nlohmann::json& was, const nlohmann::json& now);

// The names and sizes of the files frame f has in dir: {"frame_0007.png": bytes, ...}.
nlohmann::json frameFiles(const std::filesystem::path& dir, int frame);
// Whether dir holds the record's frame files with the recorded sizes.
bool frameComplete(const std::filesystem::path& dir, const nlohmann::json& record);

// The last record of each frame, in frame order.
std::vector<nlohmann::json> latestPerFrame(const std::vector<nlohmann::json>& records);

// Removes the temporaries a killed writer left in dir (.NAME.tmpPID.EXT, src/core/atomic_file).
void removeStaleTemporaries(const std::filesystem::path& dir);

}  // namespace lzb
