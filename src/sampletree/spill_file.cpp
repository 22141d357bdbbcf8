#include "src/sampletree/spill_file.hpp"

#include <algorithm>

namespace lzb::sampletree {

SpillFile::SpillFile(std::filesystem::path path, size_t buckets, uint64_t bufferTriangles)
    : file_(std::move(path)), bufferTriangles_(std::max<uint64_t>(bufferTriangles, 1)),
      buffers_(buckets), chunks_(buckets), counts_(buckets, 0) {}

void SpillFile::add(uint32_t bucket, const StreamTriangle& t) {
  if (bucket >= buffers_.size()) {
    buffers_.resize(bucket + 1);
    chunks_.resize(bucket + 1);
    counts_.resize(bucket + 1, 0);
  }
  buffers_[bucket].push_back(t);
  ++counts_[bucket];
  if (++buffered_ >= bufferTriangles_) flush();
}

void SpillFile::flush() {
  for (size_t b = 0; b < buffers_.size(); ++b) {
    std::vector<StreamTriangle>& buf = buffers_[b];
    if (buf.empty()) continue;
    chunks_[b].push_back({file_.append(buf.data(), buf.size() * sizeof(StreamTriangle)), buf.size()});
    buf = {};  // give the memory back: the next flush may find few buckets buffered
  }
  buffered_ = 0;
}

std::vector<StreamTriangle> SpillFile::read(uint32_t bucket) const {
  std::vector<StreamTriangle> out(size_t(counts_[bucket]));
  StreamTriangle* p = out.data();
  for (const Chunk& c : chunks_[bucket]) {
    file_.read(c.offset, size_t(c.count) * sizeof(StreamTriangle), p);
    p += c.count;
  }
  return out;
}

}  // namespace lzb::sampletree
