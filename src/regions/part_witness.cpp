#include "src/regions/part_witness.hpp"

#include <algorithm>
#include <limits>
#include <tuple>

#include "raycast/exact/raycast_renderer.hpp"

namespace lzb::regions {

namespace {

struct WitnessRay {
  uint64_t question;
  double dir[3];
};

struct NearestHit {
  double t;
  uint64_t id;  // the whole scene's
};

bool nearer(const NearestHit& a, const NearestHit& b) {
  return std::tie(a.t, a.id) < std::tie(b.t, b.id);
}

// MPI_Op: the nearer of each pair of hits.
void nearestOf(void* in, void* inout, int* count, MPI_Datatype*) {
  const auto* a = static_cast<const NearestHit*>(in);
  auto* b = static_cast<NearestHit*>(inout);
  for (int i = 0; i < *count; ++i)
    if (nearer(a[i], b[i])) b[i] = a[i];
}

// A datatype of `bytes` contiguous bytes (committed; the caller frees it).
MPI_Datatype bytesType(int bytes) {
  MPI_Datatype t;
  LZB_MPI_CALL(MPI_Type_contiguous(bytes, MPI_BYTE, &t));
  LZB_MPI_CALL(MPI_Type_commit(&t));
  return t;
}

bool before(const WitnessQuestion& a, const WitnessQuestion& b) {
  return std::tie(a.y, a.x, a.id) < std::tie(b.y, b.x, b.id);
}

}  // namespace

PartWitness::PartWitness(const HeldShare& held, const std::vector<const Renderer*>& references,
                         const RenderOptions& options)
    : held_(held), threads_(std::max(options.threads, 1)) {
  for (size_t p = 0; p < held.parts.size(); ++p)
    scenes_.push_back(
        held.parts[p].scene.expandedTriangles() > 0
            ? std::make_unique<WitnessScene>(held.parts[p].scene, references[p], options)
            : nullptr);
}

PartWitness::~PartWitness() = default;

bool PartWitness::sharedWithReference() const {
  return std::all_of(scenes_.begin(), scenes_.end(),
                     [](const auto& s) { return !s || s->sharedWithReference(); });
}

double PartWitness::buildSeconds() const {
  double seconds = 0.0;
  for (const auto& s : scenes_)
    if (s) seconds += s->buildSeconds();
  return seconds;
}

std::vector<uint8_t> PartWitness::answer(const mpi::Group& group, const Camera& camera,
                                         const std::vector<WitnessQuestion>& questions,
                                         std::vector<uint64_t>& raysPerRank) const {
  // The questions, to every rank.
  uint64_t count = group.root() ? questions.size() : 0;
  LZB_MPI_CALL(MPI_Bcast(&count, 1, MPI_UINT64_T, 0, group.comm));
  std::vector<WitnessQuestion> asked = group.root() ? questions : std::vector<WitnessQuestion>();
  asked.resize(size_t(count));
  MPI_Datatype questionType = bytesType(sizeof(WitnessQuestion));
  LZB_MPI_CALL(MPI_Bcast(asked.data(), int(count), questionType, 0, group.comm));
  MPI_Type_free(&questionType);

  // The rays of the triangles this rank holds (a triangle lies in one part of one rank).
  std::vector<WitnessRay> mine;
  for (uint64_t q = 0; q < count; ++q)
    for (size_t p = 0; p < held_.parts.size(); ++p) {
      const uint64_t local = held_.parts[p].ids.local(asked[size_t(q)].id);
      if (local == kNoId) continue;
      anyWitnessRay(held_.parts[p].scene, camera, asked[size_t(q)].x, asked[size_t(q)].y, local,
                    [&](const glm::dvec3& d) {
                      mine.push_back({q, {d.x, d.y, d.z}});
                      return false;  // every ray: whether one proves it is known only at the root
                    });
      break;
    }

  // Every ray to every rank.
  const int made = int(mine.size());
  std::vector<int> counts(size_t(group.size)), offsets(size_t(group.size), 0);
  LZB_MPI_CALL(MPI_Allgather(&made, 1, MPI_INT, counts.data(), 1, MPI_INT, group.comm));
  for (int r = 1; r < group.size; ++r)
    offsets[size_t(r)] = offsets[size_t(r) - 1] + counts[size_t(r) - 1];
  std::vector<WitnessRay> rays(size_t(offsets.back() + counts.back()));
  MPI_Datatype rayType = bytesType(sizeof(WitnessRay));
  LZB_MPI_CALL(MPI_Allgatherv(mine.data(), made, rayType, rays.data(), counts.data(),
                              offsets.data(), rayType, group.comm));
  MPI_Type_free(&rayType);
  if (group.root()) raysPerRank.assign(counts.begin(), counts.end());

  // Each ray's nearest hit through this rank's parts, then over the ranks.
  std::vector<NearestHit> hits(rays.size(),
                               NearestHit{std::numeric_limits<double>::infinity(), kNoId});
  const long n = long(rays.size());
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads_)
  for (long i = 0; i < n; ++i) {
    const glm::dvec3 dir(rays[size_t(i)].dir[0], rays[size_t(i)].dir[1], rays[size_t(i)].dir[2]);
    for (size_t p = 0; p < scenes_.size(); ++p) {
      if (!scenes_[p]) continue;
      const RayHit h = scenes_[p]->embree().intersect(camera.position(), dir, camera.nearPlane(),
                                                      camera.farPlane());
      const NearestHit hit{double(h.t), held_.parts[p].ids.global(h.id)};
      if (h.hit() && nearer(hit, hits[size_t(i)])) hits[size_t(i)] = hit;
    }
  }
  MPI_Datatype hitType = bytesType(sizeof(NearestHit));
  MPI_Op nearest;
  LZB_MPI_CALL(MPI_Op_create(&nearestOf, 1, &nearest));
  LZB_MPI_CALL(MPI_Reduce(group.root() ? MPI_IN_PLACE : hits.data(), hits.data(), int(hits.size()),
                          hitType, nearest, 0, group.comm));
  MPI_Op_free(&nearest);
  MPI_Type_free(&hitType);
  if (!group.root()) return {};
  std::vector<uint8_t> proven(size_t(count), 0);
  for (size_t i = 0; i < rays.size(); ++i)
    if (hits[i].id == asked[size_t(rays[i].question)].id) proven[size_t(rays[i].question)] = 1;
  return proven;
}

bool AskedWitness::visibleInPixel(int x, int y, uint64_t id) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  asked_.push_back({x, y, id});
  return false;
}

std::vector<WitnessQuestion> AskedWitness::questions() const {
  std::vector<WitnessQuestion> q = asked_;
  std::sort(q.begin(), q.end(), before);
  q.erase(std::unique(q.begin(), q.end(),
                      [](const auto& a, const auto& b) { return !before(a, b) && !before(b, a); }),
          q.end());
  return q;
}

AnsweredWitness::AnsweredWitness(std::vector<WitnessQuestion> questions,
                                 std::vector<uint8_t> proven)
    : questions_(std::move(questions)), proven_(std::move(proven)) {}

bool AnsweredWitness::visibleInPixel(int x, int y, uint64_t id) const {
  const WitnessQuestion q{x, y, id};
  const auto at = std::lower_bound(questions_.begin(), questions_.end(), q, before);
  return at != questions_.end() && !before(q, *at) && proven_[size_t(at - questions_.begin())];
}

}  // namespace lzb::regions
