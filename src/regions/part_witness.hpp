#pragma once
// The ray witness (raycast/exact/ray_witness.hpp) under --distribute data, where no rank holds
// the whole scene: the same rule, its rays made by the rank that holds the triangle asked about
// and traced by every rank through what it holds, the nearest hit over all ranks deciding.
//
// A frame's judging (judgeFrame) asks its questions (pixel, triangle) at the group's root; then
// collectively: the root sends the questions; each rank makes the rule's rays for the triangles
// it holds (through its part's copy, with the whole scene's transforms, so the same rays as the
// whole scene's); every rank gets every ray and traces it through each of its parts' Embree
// scenes; the root takes each ray's nearest hit over the ranks (least t, then least ID, as the
// depth composite) and proves a question when one of its rays first hits its triangle. Parts keep
// the whole scene's node frames, so a triangle's hit t is the whole scene's bit for bit; only a
// tie of two triangles at one t could resolve otherwise than the whole scene's BVH would.
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "mpi/group.hpp"
#include "raycast/exact/ray_witness.hpp"
#include "src/image/witness.hpp"
#include "src/regions/share.hpp"

namespace lzb::regions {

// A pixel and the triangle (the whole scene's ID) a test image shows there.
struct WitnessQuestion {
  int32_t x = 0, y = 0;
  uint64_t id = 0;
};

class PartWitness {
 public:
  // The witness scenes of this rank's parts: `references[p]`'s Embree scene where that part's
  // reference renders by raycast, else one built here (none for an empty part).
  PartWitness(const HeldShare& held, const std::vector<const Renderer*>& references,
              const RenderOptions& options);
  ~PartWitness();

  // Collective over `group`: the root's `questions` answered (true: proven visible) at the root,
  // empty elsewhere; at the root, `raysPerRank` receives the rays each rank made (its share).
  std::vector<uint8_t> answer(const mpi::Group& group, const Camera& camera,
                              const std::vector<WitnessQuestion>& questions,
                              std::vector<uint64_t>& raysPerRank) const;
  bool sharedWithReference() const;
  double buildSeconds() const;

 private:
  const HeldShare& held_;
  std::vector<std::unique_ptr<WitnessScene>> scenes_;  // per part
  int threads_;
};

// A witness that records what is asked and proves nothing (the first compare of a frame).
class AskedWitness : public VisibilityWitness {
 public:
  std::string name() const override { return RayWitness::kName; }
  bool visibleInPixel(int x, int y, uint64_t id) const override;
  // The questions asked, each once, in (y, x) order.
  std::vector<WitnessQuestion> questions() const;

 private:
  mutable std::vector<WitnessQuestion> asked_;
  mutable std::mutex mutex_;
};

// A witness answering from questions answered by PartWitness (the second compare).
class AnsweredWitness : public VisibilityWitness {
 public:
  AnsweredWitness(std::vector<WitnessQuestion> questions, std::vector<uint8_t> proven);
  std::string name() const override { return RayWitness::kName; }
  bool visibleInPixel(int x, int y, uint64_t id) const override;

 private:
  std::vector<WitnessQuestion> questions_;  // sorted as AskedWitness gives them
  std::vector<uint8_t> proven_;
};

}  // namespace lzb::regions
