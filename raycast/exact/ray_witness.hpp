#pragma once
// The ray witness (src/image/witness.hpp): proof by exact rays that a triangle is visible
// somewhere inside a pixel, the papers' definition of a correct pixel, for the pixels the
// reference's 17 samples cannot settle.
//
// The rule, for triangle T and pixel (x, y) of a camera:
//   1. T (in world space, double) is clipped to near <= view depth <= far, projected to pixel
//      coordinates (a triangle in front of the eye projects to a convex polygon) and clipped to
//      the pixel's square [x, x + 1] x [y, y + 1]: P, the points of the pixel whose line of sight
//      meets T between near and far. P empty (T does not reach the pixel): no witness, no ray.
//   2. Rays from the eye are cast through points of P, in this order: P's vertex centroid, then
//      about kWitnessRays points spread over P by area (P fanned from its centroid, each fan
//      triangle of area share s given max(1, floor(sqrt(kWitnessRays * s)))^2 lattice points at
//      the centroids of its regular subdivision, all strictly inside).
//   3. T is visible in the pixel as soon as one ray's first hit (EmbreeScene::intersect, t in
//      [near, far]: the raycast reference's own rule) is T.
// A witness is a ray through the pixel that sees T first, so every witnessed pixel is correct by
// the definition (the raycast reference would show T there at a finer sample). A part of T
// visible in less than the spacing of the points (about 1/8 of P's extent) may be missed: the
// witness proves, it never disproves, and a missed proof leaves the pixel wrong.
// Cost per pixel asked: a clip of T (no ray) when T does not reach the pixel, else at most
// 1 + kWitnessRays + 9 rays (P has at most 9 vertices, so 9 fan triangles, each of at least one
// point), stopping at the first witness. Only covered pixels whose triangle is not among the 17
// reference IDs are asked.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "raycast/exact/embree_scene.hpp"
#include "src/core/camera.hpp"
#include "src/core/renderer.hpp"
#include "src/core/scene.hpp"
#include "src/image/witness.hpp"

namespace lzb {

inline constexpr int kWitnessRays = 64;  // rays spread over P after its centroid (see above)

// Steps 1 and 2 of the rule for triangle `id` of `scene` and pixel (x, y): calls ray(direction)
// for each ray from camera.position() in the rule's order until it returns true; false when none
// did (or `id` is not in the scene, or T does not reach the pixel).
bool anyWitnessRay(const Scene& scene, const Camera& camera, int x, int y, uint64_t id,
                   const std::function<bool(const glm::dvec3&)>& ray);

// The witness for one frame: scene, its Embree scene and the frame's camera, all borrowed.
class RayWitness : public VisibilityWitness {
 public:
  RayWitness(const Scene& scene, const EmbreeScene& embree, const Camera& camera)
      : scene_(scene), embree_(embree), camera_(camera) {}
  static constexpr const char* kName = "rays";  // the report's "witness"
  std::string name() const override { return kName; }
  // The rule above; false for an ID that is not in the scene. Thread-safe.
  bool visibleInPixel(int x, int y, uint64_t id) const override;

 private:
  const Scene& scene_;
  const EmbreeScene& embree_;
  Camera camera_;
};

// The Embree scene the witness traces, made once per run: the raycast reference's own when the
// reference is a RaycastRenderer (no second build), else one built here as the raycast reference
// would build it under `options` (its threads and --bvh).
class WitnessScene {
 public:
  WitnessScene(const Scene& scene, const Renderer* reference, const RenderOptions& options);
  RayWitness witness(const Camera& camera) const { return RayWitness(scene_, *embree_, camera); }
  const EmbreeScene& embree() const { return *embree_; }
  bool sharedWithReference() const { return !owned_; }
  double buildSeconds() const { return owned_ ? owned_->buildStats().seconds : 0.0; }

 private:
  const Scene& scene_;
  std::unique_ptr<EmbreeScene> owned_;
  const EmbreeScene* embree_ = nullptr;
};

}  // namespace lzb
