#pragma once
// The external construction's writing pass (section 5.1): every triangle appended to its bucket,
// buffered in memory and flushed in chunks to one scratch file, so each bucket can be read back
// alone, in input order. The file is removed when the object goes.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "src/sampletree/scratch_file.hpp"
#include "src/sampletree/triangle_stream.hpp"

namespace lzb::sampletree {

class SpillFile {
 public:
  // bufferTriangles: how many triangles are held before a flush (the memory it may use / 48).
  // Adding to a bucket past `buckets` adds buckets.
  SpillFile(std::filesystem::path path, size_t buckets, uint64_t bufferTriangles);

  void add(uint32_t bucket, const StreamTriangle& t);
  // Flushes what is buffered; call before reading.
  void flush();
  // The bucket's triangles in the order they were added.
  std::vector<StreamTriangle> read(uint32_t bucket) const;
  uint64_t count(uint32_t bucket) const { return counts_[bucket]; }
  size_t buckets() const { return counts_.size(); }
  uint64_t bytesWritten() const { return file_.size(); }

 private:
  struct Chunk {
    uint64_t offset, count;
  };
  ScratchFile file_;
  uint64_t bufferTriangles_, buffered_ = 0;
  std::vector<std::vector<StreamTriangle>> buffers_;
  std::vector<std::vector<Chunk>> chunks_;
  std::vector<uint64_t> counts_;
};

}  // namespace lzb::sampletree
