#pragma once
// Small collectives over strings, flags and boxes (reports, messages, root-only checks, what the
// ranks reading a file in slices agree on).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "mpi/group.hpp"
#include "src/core/bounds.hpp"

namespace lzb::mpi {

// Gathers one string per rank at the root (empty vector elsewhere).
std::vector<std::string> gatherStrings(const Group& g, const std::string& mine);
// Broadcasts a flag from the root so every rank takes the same branch after a root-only check.
bool broadcastFlag(const Group& g, bool value);
// `value` of rank `from` (the root by default), on every rank.
std::string broadcastString(const Group& g, const std::string& value, int from = 0);
// MPI_Allreduce in place of `n` items (none: no call).
void allreduceInPlace(const Group& g, void* data, size_t n, MPI_Datatype type, MPI_Op op);
// Each box made the box around every rank's (empty ones included: a box empty on every rank stays
// empty), in one reduction.
void boundsOverRanks(const Group& g, std::span<Bounds> boxes);
Bounds boundsOverRanks(const Group& g, Bounds box);

}  // namespace lzb::mpi
