#pragma once
// The representative colour of a node (section 4.4): the area-weighted median of its triangles'
// colours (ordered by luminance, ties by ID), as the paper's implementation takes it. The median is
// one of the triangles' own colours, so the node keeps that triangle: its ID is what the node's
// splat writes, lit like the triangle (tree_shading.hpp: the node keeps its shading inputs).
#include <cstdint>
#include <span>

#include "src/sampletree/tree_input.hpp"

namespace lzb::sampletree {

// Index (into `in`) of the triangle whose colour is the area-weighted median of `tris`; tris must
// not be empty.
uint32_t medianTriangle(const TriangleInput& in, const std::vector<double>& areas,
                        std::span<const uint32_t> tris);

}  // namespace lzb::sampletree
