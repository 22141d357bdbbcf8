#pragma once
// Bottom-up sampling (Fig. 3 and section 5.2): every inner node u, after its children, makes
// m_u = q_u ln q_u + c q_u drawings, each a triangle of its children's remaining triangles picked
// with probability proportional to area; the triangles drawn (each once) move from the children
// to u. q_u = ceil(A(P(u)) / A(B(u))), A(B(u)) the area of one face of u's cell (Theorem 1).
#include <cstdint>
#include <vector>

#include "src/sampletree/cell_octree.hpp"

namespace lzb::sampletree {

// q_u for a cell of side `side` whose triangles have total area `area` (at least 1).
uint64_t sampleFactor(double area, double side);
// ceil(q ln q + c q): the drawings of Theorem 1 (at most 2^32 - 1).
uint32_t sampleDraws(uint64_t q, double c);

// The Philox counter key of a node: its level and cell, so the drawings depend on the node only.
uint64_t nodeKey(const BuildNode& n);

// Samples every inner node of the octree, deepest first. Randomness: Philox keyed by (seed, node
// key, drawing), so the tree does not depend on the thread count.
void drawSamples(CellOctree& tree, const std::vector<double>& areas, double c, uint64_t seed,
                 int threads);

}  // namespace lzb::sampletree
