#pragma once
// Packed RGBA8 colours (R in the lowest byte, so the bytes in memory read R, G, B, A as GL_RGBA).
#include <algorithm>
#include <cstdint>
#include <glm/vec3.hpp>

namespace lzb {

using Rgba8 = uint32_t;

constexpr Rgba8 packRgba8(uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24;
}

inline uint8_t unitToByte(float v) { return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

inline Rgba8 packRgb(const glm::vec3& c) {
  return packRgba8(unitToByte(c.r), unitToByte(c.g), unitToByte(c.b));
}

inline glm::vec3 unpackRgb(Rgba8 c) {
  return glm::vec3(float(c & 255), float(c >> 8 & 255), float(c >> 16 & 255)) / 255.0f;
}

constexpr uint8_t channel(Rgba8 c, int i) { return uint8_t(c >> (8 * i)); }

}  // namespace lzb
