#pragma once
// A visibility witness: proof that a triangle is visible somewhere inside a pixel, for the pixels
// the reference's 17 samples cannot settle (metrics.hpp). src/image knows only this interface;
// raycast/ray_witness.hpp implements it with exact rays (no Embree here).
#include <cstdint>
#include <string>

namespace lzb {

class VisibilityWitness {
 public:
  virtual ~VisibilityWitness() = default;
  // The rule's name, the accuracy object's "witness" field (e.g. "rays").
  virtual std::string name() const = 0;
  // True only with proof that triangle `id` is visible inside pixel (x, y) of the frame the
  // witness was made for; false means no proof was found. Called from many threads at once, and
  // must give the same answer every time (accuracy counts are deterministic).
  virtual bool visibleInPixel(int x, int y, uint64_t id) const = 0;
};

}  // namespace lzb
