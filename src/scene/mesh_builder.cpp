#include "src/scene/mesh_builder.hpp"

#include <bit>
#include <cmath>
#include <numbers>

namespace lzb {

namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

bool MeshBuilder::triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                           Rgba8 color) {
  const glm::vec3 fa(a), fb(b), fc(c);
  // Checked after rounding: a finite double beyond float range becomes Inf.
  if (!finite(glm::dvec3(fa)) || !finite(glm::dvec3(fb)) || !finite(glm::dvec3(fc))) {
    ++stats_.nonFinite;
    return false;
  }
  if (!keepsTriangle(fa, fb, fc)) {
    ++stats_.degenerate;
    return false;
  }
  // A mesh emptied since (a streamed chunk handed out) holds none of the recent vertices.
  if (mesh_.positions.empty() || recent_.empty()) recent_.assign(size_t(1) << kSlotBits, Slot{});
  const uint32_t i = shared(fa), j = shared(fb), k = shared(fc);
  mesh_.addTriangle(i, j, k, color);
  ++stats_.loaded;
  return true;
}

uint32_t MeshBuilder::shared(const glm::vec3& p) {
  const Bits bits{std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                  std::bit_cast<uint32_t>(p.z)};
  // MurmurHash3's 64-bit finaliser: a product sum of the bits alone clusters a sphere's
  // corners into a few slots.
  uint64_t h =
      (uint64_t(bits[0]) | uint64_t(bits[1]) << 32) ^ uint64_t(bits[2]) * 0x9E3779B97F4A7C15u;
  h = (h ^ h >> 33) * 0xFF51AFD7ED558CCDu;
  h = (h ^ h >> 33) * 0xC4CEB9FE1A85EC53u;
  Slot& slot = recent_[(h ^ h >> 33) >> (64 - kSlotBits)];
  if (slot.vertex < mesh_.positions.size() && slot.bits == bits) return slot.vertex;
  slot = {bits, mesh_.addVertex(p)};
  return slot.vertex;
}

void MeshBuilder::quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const glm::dvec3& d, const glm::dvec3& outward, Rgba8 color) {
  if (glm::dot(glm::cross(b - a, c - a), outward) >= 0.0) {
    triangle(a, b, c, color);
    triangle(a, c, d, color);
  } else {
    triangle(a, c, b, color);
    triangle(a, d, c, color);
  }
}

void MeshBuilder::box(const Bounds& b, Rgba8 color, bool bottom) {
  const glm::dvec3 &l = b.lo, &h = b.hi;
  quad({l.x, l.y, l.z}, {l.x, h.y, l.z}, {l.x, h.y, h.z}, {l.x, l.y, h.z}, {-1, 0, 0}, color);
  quad({h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z}, {1, 0, 0}, color);
  quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, h.y, l.z}, {l.x, h.y, l.z}, {0, 0, -1}, color);
  quad({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 0, 1}, color);
  quad({l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z}, {0, 1, 0}, color);
  if (bottom)
    quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z}, {0, -1, 0}, color);
}

void MeshBuilder::sphere(int slices, int stacks, Rgba8 color) {
  const double pi = std::numbers::pi;
  const auto point = [&](int stack, int slice) {
    const double theta = pi * stack / stacks, phi = 2.0 * pi * slice / slices;
    return glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                      std::cos(theta));
  };
  // Wound so the normal points away from the centre.
  const auto outward = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) >= 0.0)
      triangle(a, b, c, color);
    else
      triangle(a, c, b, color);
  };
  for (int st = 0; st < stacks; ++st)
    for (int sl = 0; sl < slices; ++sl) {
      const glm::dvec3 a = point(st, sl), b = point(st + 1, sl), c = point(st + 1, sl + 1),
                       d = point(st, sl + 1);
      if (st > 0) outward(a, b, d);           // the top pole row is one triangle per slice
      if (st < stacks - 1) outward(b, c, d);  // and so is the bottom one
    }
}

}  // namespace lzb
