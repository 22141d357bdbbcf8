#include "src/sampletree/triangle_stream.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace lzb::sampletree {

namespace {

constexpr size_t kBatch = 1 << 16;  // triangles handed to a sink at once

// A node-frame vertex in the world, as every stream of a placed node computes it.
glm::vec3 placed(const glm::dmat4& transform, const glm::vec3& v) {
  return glm::vec3(transform * glm::dvec4(glm::dvec3(v), 1.0));
}

}  // namespace

void SceneStream::forEach(const TriangleSink& sink) const {
  std::vector<StreamTriangle> batch;
  batch.reserve(kBatch);
  for (const DrawItem& item : flattenScene(scene_)) {
    const Mesh& mesh = scene_.nodes[item.node].mesh;
    for (size_t t = 0; t < mesh.size(); ++t) {
      StreamTriangle s;
      for (int k = 0; k < 3; ++k) s.v[k] = placed(item.transform, mesh.vertex(t, k));
      s.colour = mesh.color(t);
      s.id = item.idBase + t;
      batch.push_back(s);
      if (batch.size() == kBatch) sink(batch), batch.clear();
    }
  }
  if (!batch.empty()) sink(batch);
}

void MeshChunkStream::forEach(const TriangleSink& sink) const {
  uint64_t next = 0;
  std::vector<StreamTriangle> batch;
  const bool first = !passed_;
  const LoadStats stats = source_([&](const Mesh& mesh) {
    if (first)
      for (const glm::vec3& p : mesh.positions) nodeBounds_.extend(glm::dvec3(p));
    batch.resize(mesh.size());
    for (size_t t = 0; t < mesh.size(); ++t) {
      for (int k = 0; k < 3; ++k) batch[t].v[k] = placed(placement_, mesh.vertex(t, k));
      batch[t].colour = mesh.color(t);
      batch[t].id = next++;
    }
    sink(batch);
  });
  outline_.stats = stats;
  outline_.uniqueTriangles = outline_.expandedTriangles = next;
  passed_ = true;
}

SceneOutline MeshChunkStream::outline() const {
  if (!passed_) throw std::logic_error("MeshChunkStream: the outline needs a pass first");
  return placedMeshOutline(outline_, nodeBounds_, placement_, outline_.uniqueTriangles,
                           outline_.stats);
}

namespace {

// The queue between the reading thread and the sink.
struct BatchQueue {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::vector<StreamTriangle>> batches;
  bool finished = false, cancelled = false;
  std::exception_ptr error;
};

struct Cancelled {};

}  // namespace

void ReadAheadStream::forEach(const TriangleSink& sink) const {
  BatchQueue q;
  std::thread reader([&] {
    try {
      in_.forEach([&](std::span<const StreamTriangle> batch) {
        std::unique_lock lock(q.mutex);
        q.changed.wait(lock, [&] { return q.batches.size() < depth_ || q.cancelled; });
        if (q.cancelled) throw Cancelled{};
        q.batches.emplace_back(batch.begin(), batch.end());
        q.changed.notify_all();
      });
    } catch (const Cancelled&) {
    } catch (...) {
      q.error = std::current_exception();
    }
    std::lock_guard lock(q.mutex);
    q.finished = true;
    q.changed.notify_all();
  });
  try {
    for (;;) {
      std::vector<StreamTriangle> batch;
      {
        std::unique_lock lock(q.mutex);
        q.changed.wait(lock, [&] { return !q.batches.empty() || q.finished; });
        if (q.batches.empty()) break;
        batch = std::move(q.batches.front());
        q.batches.pop_front();
        q.changed.notify_all();
      }
      sink(batch);
    }
  } catch (...) {
    {
      std::lock_guard lock(q.mutex);
      q.cancelled = true;
      q.changed.notify_all();
    }
    reader.join();
    throw;
  }
  reader.join();
  if (q.error) std::rethrow_exception(q.error);
}

CopiedStream::CopiedStream(const TriangleStream& in, std::filesystem::path copy)
    : in_(in), copy_(std::make_unique<ScratchFile>(std::move(copy))) {}

CopiedStream::~CopiedStream() = default;

void CopiedStream::drop() { copy_.reset(); }

void CopiedStream::forEach(const TriangleSink& sink) const {
  if (!copied_) {
    in_.forEach([&](std::span<const StreamTriangle> batch) {
      copy_->append(batch.data(), batch.size_bytes());
      sink(batch);
    });
    copied_ = true;
    return;
  }
  std::vector<StreamTriangle> batch;
  const uint64_t total = copy_->size() / sizeof(StreamTriangle);
  for (uint64_t done = 0; done < total; done += kBatch) {
    batch.resize(size_t(std::min<uint64_t>(kBatch, total - done)));
    copy_->read(done * sizeof(StreamTriangle), batch.size() * sizeof(StreamTriangle), batch.data());
    sink(batch);
  }
}

}  // namespace lzb::sampletree
