#pragma once
// Building a sample tree in memory: gather the triangles, build the octree (cell_octree.hpp),
// sample bottom-up (sample_draw.hpp), choose each node's representative (representative.hpp) and
// lay the nodes out in preorder, dropping subtrees left without triangles.
#include "src/core/scene.hpp"
#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/tree_input.hpp"

namespace lzb::sampletree {

// Throws InputError when c is not in [0, 50] or leafTriangles is 0.
void validateParams(const TreeParams& params);

SampleTree buildTree(const TriangleInput& in, const TreeParams& params, int threads);
// The scene's expanded triangles (refused above kMaxInCoreTriangles, InputError).
SampleTree buildTree(const Scene& scene, const TreeParams& params, int threads);

}  // namespace lzb::sampletree
