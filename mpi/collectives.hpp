#pragma once
// Small collectives over strings and flags (reports, messages, root-only checks).
#include <string>
#include <vector>

#include "mpi/group.hpp"

namespace lzb::mpi {

// Gathers one string per rank at the root (empty vector elsewhere).
std::vector<std::string> gatherStrings(const Group& g, const std::string& mine);
// Broadcasts a flag from the root so every rank takes the same branch after a root-only check.
bool broadcastFlag(const Group& g, bool value);
std::string broadcastString(const Group& g, const std::string& value);

}  // namespace lzb::mpi
