#include "src/cli/frame_record.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <sstream>

#include "src/core/error.hpp"
#include "src/core/whole_file.hpp"
#include "src/image/frame_io.hpp"

namespace lzb {

namespace fs = std::filesystem;

namespace {

// A whole non-negative decimal integer, else -1.
int wholeNumber(const std::string& text) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    return -1;
  return std::stoi(text);
}

// The record's JSON object, or null when the line is not one.
nlohmann::json parseRecord(const std::string& line) {
  nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
  return record.is_object() && record.contains("frame") ? record : nlohmann::json();
}

// Bytes of `text` up to and including its last newline: a record is written with its newline
// in one write, so a line without one is torn.
size_t wholeLength(const std::string& text) {
  const size_t lastNewline = text.rfind('\n');
  return lastNewline == std::string::npos ? 0 : lastNewline + 1;
}

std::string shown(const nlohmann::json& value) {
  return value.is_string() ? value.get<std::string>() : value.dump();
}

}  // namespace

FrameRange parseFrameRange(const std::string& text, int frames, const std::string& field) {
  if (text.empty()) return {0, frames};
  const size_t colon = text.find(':');
  const int begin = colon == std::string::npos ? -1 : wholeNumber(text.substr(0, colon));
  const std::string tail = colon == std::string::npos ? "" : text.substr(colon + 1);
  const int end = tail.empty() ? frames : wholeNumber(tail);
  require(begin >= 0 && end >= 0 && begin < end && end <= frames, field + " " + text,
          "must be A:B or A: with 0 <= A < B <= --frames (" + std::to_string(frames) + ")");
  return {begin, end};
}

std::vector<nlohmann::json> readFrameRecords(const fs::path& file) {
  std::vector<nlohmann::json> records;
  std::error_code ec;
  if (!fs::exists(file, ec)) return records;
  const std::string text = readWholeFile(file, "cannot be read");
  std::istringstream lines(text.substr(0, wholeLength(text)));
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    nlohmann::json record = parseRecord(line);
    require(!record.is_null(), file.string() + ":" + std::to_string(number),
            "not a frame record (damaged; remove the line to go on)");
    records.push_back(std::move(record));
  }
  return records;
}

void trimTornLine(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) return;
  const std::string text = readWholeFile(file, "cannot be read");
  const size_t keep = wholeLength(text);
  if (keep != text.size()) fs::resize_file(file, keep, ec);
  require(!ec, file.string(), "cannot cut its torn last line: " + ec.message());
}

FrameRecordWriter::FrameRecordWriter(const fs::path& file) : path_(file.string()) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  require(fd_ >= 0, path_, std::string("cannot open for appending: ") + std::strerror(errno));
}

FrameRecordWriter::~FrameRecordWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void FrameRecordWriter::append(const nlohmann::json& record) {
  const std::string line = record.dump() + "\n";
  // One write: with O_APPEND the line lands whole after every earlier one (a short write, on a
  // full disk or a kill, leaves a torn last line that readers drop).
  const ssize_t wrote = ::write(fd_, line.data(), line.size());
  require(wrote == ssize_t(line.size()), path_,
          "cannot append a frame record: " +
              std::string(wrote < 0 ? std::strerror(errno) : "short write"));
}

nlohmann::json imageKey(const nlohmann::json& head) {
  const nlohmann::json& p = head.at("parameters");
  nlohmann::json key = {{"scene", head.at("scene").at("source")},
                        {"triangles_unique", head.at("scene").at("triangles_unique")},
                        {"triangles_expanded", head.at("scene").at("triangles_expanded")},
                        {"method", head.at("method")},
                        {"method_parameters", head.at("method_parameters")},
                        {"width", head.at("width")},
                        {"height", head.at("height")}};
  for (const char* field :
       {"seed", "quality", "frames", "reference", "subsamples", "fov", "near", "far"})
    key[field] = p.at(field);
  key["bvh"] =
      p.value("bvh", "fast");  // compact leaves compute t otherwise (records before it: fast)
  // Exact methods give the replicated image under data too; the others draw each region apart.
  if (!head.value("method_exact", false)) {
    key["distribution"] = head.at("distribution");
    key["regions"] = p.at("regions");
  }
  return key;
}

std::string keyDifference(const nlohmann::json& was, const nlohmann::json& now) {
  for (const auto& [field, value] : now.items()) {
    if (!was.contains(field)) return field + ": not recorded, now " + shown(value);
    if (was[field] != value) return field + ": was " + shown(was[field]) + ", now " + shown(value);
  }
  for (const auto& [field, value] : was.items())
    if (!now.contains(field)) return field + ": was " + shown(value) + ", now not given";
  return "";
}

nlohmann::json frameFiles(const fs::path& dir, int frame) {
  nlohmann::json files = nlohmann::json::object();
  for (const char* extension : {".png", ".exr"}) {
    const std::string name = frameStem(frame) + extension;
    files[name] = fs::file_size(dir / name);
  }
  return files;
}

bool frameComplete(const fs::path& dir, const nlohmann::json& record) {
  if (!record.contains("files") || !record["files"].is_object()) return false;
  for (const auto& [name, bytes] : record["files"].items()) {
    std::error_code ec;
    const uintmax_t size = fs::file_size(dir / name, ec);
    if (ec || !bytes.is_number_unsigned() || size != bytes.get<uintmax_t>()) return false;
  }
  return !record["files"].empty();
}

std::vector<nlohmann::json> latestPerFrame(const std::vector<nlohmann::json>& records) {
  std::map<int, const nlohmann::json*> latest;
  for (const nlohmann::json& r : records) latest[r.at("frame").get<int>()] = &r;
  std::vector<nlohmann::json> frames;
  for (const auto& [frame, record] : latest) frames.push_back(*record);
  return frames;
}

void removeStaleTemporaries(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(".frame_", 0) == 0 && name.find(".tmp") != std::string::npos)
      fs::remove(entry.path(), ec);
  }
}

}  // namespace lzb
