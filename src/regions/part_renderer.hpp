#pragma once
// The renderer of a rank's share under --distribute data: one renderer per part (share.hpp), each
// rendering the whole frame of its part; the parts are composited by depth with the whole scene's
// IDs, and each pixel is shaded once by the part that won it. A probing method's frame way
// (src/core/frame_probe.hpp) is reduced over every part of every rank first.
#include <memory>
#include <string>
#include <vector>

#include "src/core/renderer.hpp"
#include "src/regions/share.hpp"

namespace lzb::regions {

// A renderer of a rank's parts, wrapping one renderer per part (`inner[p]` made on
// held.parts[p].scene; none for an empty part): it renders the whole frame of each part,
// composites the parts by depth with the whole scene's IDs, then shades each pixel once by the
// part that won it. Its set-up reports the regions and triangles this rank holds.
std::unique_ptr<Renderer> makePartRenderer(const HeldShare& held,
                                           std::vector<std::unique_ptr<Renderer>> inner,
                                           const std::string& method);

}  // namespace lzb::regions
