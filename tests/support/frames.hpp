#pragma once
// The tests' frame checks: equality at three strengths (each caller keeps the one it asserted)
// and the counts of covered and missing pixels.
#include <cstddef>

#include "src/core/framebuffer.hpp"

namespace lzb::test {

// The compositing keys: IDs equal, depths bit for bit.
bool sameKeys(const Framebuffer& a, const Framebuffer& b);
// The whole image: sizes, IDs, depths bit for bit, and colour.
bool sameImage(const Framebuffer& a, const Framebuffer& b);
// IDs equal, depths equal as numbers (any two infinities alike); colour not compared.
bool sameIdsAndDepths(const Framebuffer& a, const Framebuffer& b);

// Pixels the exact frame covers and `image` leaves empty.
size_t holes(const Framebuffer& image, const Framebuffer& exact);
size_t covered(const Framebuffer& f);

}  // namespace lzb::test
