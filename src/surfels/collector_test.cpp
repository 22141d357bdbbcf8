// The surfel collector: the paper's bit split between key and data, an exact round trip of the
// quantized fields, quantization errors within their bounds, and the shuffled order.
#include "src/surfels/collector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "src/surfels/normal_quantizer.hpp"
#include "src/surfels/surfelize.hpp"

namespace lzb::surfels {
namespace {

std::vector<Surfel> randomSurfels(const CollectorLayout& l, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Surfel> out(n);
  for (Surfel& s : out) {
    s.x = uint32_t(rng()) & (l.lattice() - 1);
    s.y = uint32_t(rng()) & (l.lattice() - 1);
    s.z = uint32_t(rng()) & (l.lattice() - 1);
    s.normal = uint32_t(rng()) & ((1u << l.normalBits()) - 1);
    s.colour = uint32_t(rng()) & ((1u << 3 * l.colourBits) - 1);
  }
  return out;
}

TEST(SurfelCollector, SplitsTheBitsAsThePaper) {
  const CollectorLayout low = CollectorLayout::of(CollectorQuality::kLow),
                        high = CollectorLayout::of(CollectorQuality::kHigh);
  EXPECT_EQ(3 * low.positionBits + low.normalBits() + 3 * low.colourBits, 44);  // 24 + 11 + 9
  EXPECT_EQ(low.keyBits, 12);
  EXPECT_EQ(low.dataBits(), 32);
  EXPECT_EQ(low.entryBytes, 4);
  EXPECT_EQ(3 * high.positionBits + high.normalBits() + 3 * high.colourBits, 63);  // 30 + 15 + 18
  EXPECT_EQ(high.keyBits, 15);
  EXPECT_EQ(high.dataBits(), 48);
  EXPECT_EQ(high.entryBytes, 6);
  for (CollectorQuality q : {CollectorQuality::kLow, CollectorQuality::kHigh}) {
    const CollectorLayout l = CollectorLayout::of(q);
    for (int shift = 0; shift <= l.positionBits - 4; ++shift)
      for (const Surfel& s : randomSurfels(l, 2000, 3)) {
        uint32_t key;
        uint64_t data;
        SurfelCollector::pack(l, shift, s, key, data);
        ASSERT_LT(key, 1u << l.keyBits);
        ASSERT_LT(data, uint64_t(1) << l.dataBits());
        // The key holds 4 bits of each coordinate from the shift on (and, high, the normal's
        // octant): surfels of one key share those bits.
        uint32_t lx, ly, lz;
        unshuffleKey(q == CollectorQuality::kHigh ? key >> 3 : key, lx, ly, lz);
        EXPECT_EQ(lx, s.x >> shift & 15u);
        EXPECT_EQ(lz, s.z >> shift & 15u);
        if (q == CollectorQuality::kHigh) {
          EXPECT_EQ(key & 7u, s.normal >> 12);
        }
        EXPECT_EQ(SurfelCollector::unpack(l, shift, key, data), s);
      }
  }
}

TEST(SurfelCollector, HoldsEverySurfelWithItsTriangleOnce) {
  for (CollectorQuality q : {CollectorQuality::kLow, CollectorQuality::kHigh}) {
    const CollectorLayout l = CollectorLayout::of(q);
    const std::vector<Surfel> in = randomSurfels(l, 30000, 11);
    std::vector<uint32_t> tris(in.size());
    for (size_t i = 0; i < tris.size(); ++i) tris[i] = uint32_t(i * 7919 % 70001);  // 4-byte table
    const SurfelCollector c(q, 2, in, tris);
    EXPECT_EQ(c.size(), in.size());
    EXPECT_EQ(c.triangleBytes(), 4);
    EXPECT_EQ(c.entryBytes(), in.size() * uint64_t(l.entryBytes));
    std::vector<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>> got, want;
    for (uint32_t key = 0; key < c.keys(); ++key)
      for (uint64_t i = c.start(key); i < c.start(key + 1); ++i) {
        const Surfel s = c.surfel(key, i);
        got.emplace_back(s.x, s.y, s.z, s.normal, s.colour, c.triangle(i));
      }
    for (size_t i = 0; i < in.size(); ++i)
      want.emplace_back(in[i].x, in[i].y, in[i].z, in[i].normal, in[i].colour, tris[i]);
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want);
  }
}

TEST(SurfelCollector, SideTableIsAsNarrowAsTheTriangleCount) {
  const CollectorLayout l = CollectorLayout::of(CollectorQuality::kLow);
  const std::vector<Surfel> in = randomSurfels(l, 10, 1);
  EXPECT_EQ(SurfelCollector(CollectorQuality::kLow, 0, in, std::vector<uint32_t>(10, 255)).triangleBytes(),
            1);
  EXPECT_EQ(SurfelCollector(CollectorQuality::kLow, 0, in, std::vector<uint32_t>(10, 65535)).triangleBytes(),
            2);
  const SurfelCollector wide(CollectorQuality::kLow, 0, in, std::vector<uint32_t>(10, 65536));
  EXPECT_EQ(wide.triangleBytes(), 4);
  EXPECT_EQ(wide.triangle(9), 65536u);
}

// Object-space surfels through the collector and back: position within half a lattice step per
// axis, normal within the quantizer's bound, colour within half a colour step per channel.
TEST(SurfelCollector, RoundTripStaysWithinTheQuantizationBounds) {
  Mesh box;  // only its bounds matter: the domain
  box.add({-2.0f, -1.0f, 0.5f}, {3.0f, 0.0f, 0.5f}, {0.0f, 2.5f, 4.0f}, 0);
  const Domain d = Domain::around(box);
  for (CollectorQuality q : {CollectorQuality::kLow, CollectorQuality::kHigh}) {
    const CollectorLayout l = CollectorLayout::of(q);
    const OctahedralNormals normals(l.normalLevels);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Surfel> in;
    std::vector<glm::dvec3> points, dirs, colours;
    const double step = d.side / l.lattice();
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec3 p = d.origin + d.side * glm::dvec3(u(rng), u(rng), u(rng));
      const glm::dvec3 n = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
      const glm::dvec3 c(255.0 * u(rng), 255.0 * u(rng), 255.0 * u(rng));
      Surfel s;
      const glm::dvec3 lattice = glm::floor((p - d.origin) / step);
      s.x = uint32_t(lattice.x);
      s.y = uint32_t(lattice.y);
      s.z = uint32_t(lattice.z);
      s.normal = normals.encode(n);
      s.colour = encodeColour(c.r, c.g, c.b, l.colourBits);
      in.push_back(s);
      points.push_back(p);
      dirs.push_back(n);
      colours.push_back(c);
    }
    std::vector<uint32_t> index(in.size());
    for (uint32_t i = 0; i < index.size(); ++i) index[i] = i;
    const SurfelCollector c(q, 0, in, index);
    const double colourStep = 255.0 / double((1 << l.colourBits) - 1);
    for (uint32_t key = 0; key < c.keys(); ++key)
      for (uint64_t e = c.start(key); e < c.start(key + 1); ++e) {
        const Surfel s = c.surfel(key, e);
        const uint32_t i = c.triangle(e);
        const glm::dvec3 back = d.origin + (glm::dvec3(s.x, s.y, s.z) + 0.5) * step;
        for (int k = 0; k < 3; ++k)
          ASSERT_LE(std::abs(back[k] - points[i][k]), 0.5 * step * (1 + 1e-9));
        const glm::dvec3 n(normals.decode(s.normal));
        ASSERT_LE(std::atan2(glm::length(glm::cross(n, dirs[i])), glm::dot(n, dirs[i])),
                  normals.maxErrorBound() + 1e-6);
        uint8_t rgb[3];
        decodeColour(s.colour, l.colourBits, rgb);
        for (int k = 0; k < 3; ++k)
          ASSERT_LE(std::abs(rgb[k] - colours[i][k]), 0.5 * colourStep + 0.5);
      }
  }
}

// The table's order: key 0 holds one cell in 16 per axis, the first 8 keys one in 8, the first 64
// one in 4: a prefix of the table is spread over the whole object.
TEST(SurfelCollector, KeyOrderRefinesCoarseToFine) {
  for (int stride : {8, 4, 2, 1}) {
    const uint32_t keys = (16 / stride) * (16 / stride) * (16 / stride);
    std::vector<bool> seen(4096, false);
    for (uint32_t k = 0; k < keys; ++k) {
      uint32_t x, y, z;
      unshuffleKey(k, x, y, z);
      EXPECT_EQ(x % stride, 0u);
      EXPECT_EQ(y % stride, 0u);
      EXPECT_EQ(z % stride, 0u);
      seen[x | y << 4 | z << 8] = true;
      EXPECT_EQ(shuffleKey(x, y, z), k);
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), true), keys);
  }
}

}  // namespace
}  // namespace lzb::surfels
