#pragma once
// The sample tree shades its own pixels from its own triangles, never from the scene, so a render
// from a store holds no scene (the scene's outline stands for it, src/core/scene_outline.hpp).
// The rule is shade() (src/core/shading.hpp) with the normal and the facing point taken from the
// triangle's stored world positions (shadingInputs): a pure function of the stored triangle, so a
// splat (its node's representative triangle, whose inputs the node keeps) and that triangle drawn
// elsewhere give the same colour, on any rank. Each rank shades its own pixels before compositing
// (the renderer's colour travels with the key), and records, after each soup it draws, the inputs
// of the triangles its framebuffer then shows: a pixel's final triangle is always among them.
#include <absl/container/flat_hash_map.h>
#include <absl/container/flat_hash_set.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/color.hpp"
#include "src/core/framebuffer.hpp"
#include "src/core/scene.hpp"
#include "src/sampletree/sample_tree.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::sampletree {

struct ShadingInputs {
  glm::vec3 normal;  // unit, from the stored positions
  glm::vec3 point;   // the centroid: the facing test's point and a splat's position
};
ShadingInputs shadingInputs(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// Triangles as drawn: world positions (3 each), IDs and colours, the parts in `ranges`.
struct ColouredSoup {
  std::span<const glm::vec3> positions;
  std::span<const uint64_t> ids;
  std::span<const Rgba8> colours;
  std::span<const SoupRange> ranges;
};

class TreeShading {
 public:
  // Forgets the last frame's triangles.
  void begin() { known_.clear(); }
  // The splats of `nodes`: their representative triangles' inputs, kept in the nodes.
  void addRepresentatives(const SampleTree& table, std::span<const uint32_t> nodes);
  // After `soup` was drawn into fb: keeps the inputs of its triangles that fb shows now.
  void keepShown(const Framebuffer& fb, const ColouredSoup& soup, int threads);
  // Fills fb.color from fb.id; throws std::logic_error for a pixel whose triangle was not kept.
  void shade(const Camera& camera, const Light& light, Framebuffer& fb, int threads) const;
  size_t kept() const { return known_.size(); }

 private:
  struct Entry {
    ShadingInputs inputs;
    Rgba8 colour;
  };
  absl::flat_hash_set<uint64_t> unknownShown(const Framebuffer& fb) const;
  absl::flat_hash_map<uint64_t, Entry> known_;
};

}  // namespace lzb::sampletree
