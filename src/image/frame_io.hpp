#pragma once
// Frame images on disk: an 8-bit PNG to look at and an EXR that keeps everything exactly.
//
// frame_NNNN.png  R, G, B, A as 8 bits, straight (unassociated) alpha, the framebuffer's colour
//                 bytes as they are (empty pixels hold kBackground: alpha 0).
// frame_NNNN.exr  R, G, B, A  half, byte / 255 (reads back to the same byte exactly);
//                 Z           float, the view depth of camera.hpp, +inf where empty (OpenEXR
//                             stores the IEEE bits, so +inf survives the round trip);
//                 ID          uint32, low 32 bits of the expanded triangle ID;
//                 ID.hi       uint32, high 32 bits (so kNoId reads ID = ID.hi = 0xffffffff).
// A reference frame (`lzb render --subsamples`, reference.hpp) adds to the EXR
//                 sub.ID.k    uint32, k = 0..15: low 32 bits of sub-sample k = a + 4b's ID;
//                 sub.ID.hi.k uint32: its high 32 bits;
//                 R.aa G.aa B.aa  float: the box-filtered colour (mean of the 16 sub-samples'
//                             bytes) / 255. Float, not half: those means step by 1/16 of a byte,
//                             finer than half holds above 0.5, and read back exactly from float.
// Header attributes (`lzb render` writes them for every frame; FrameOrigin):
//                 lzb.camera.position, .look_at, .up  double[3] (OpenEXR v3d)
//                 lzb.camera.fov, .near, .far         double (degrees; view depths)
//                 lzb.camera.width, .height           int (the image's size)
//                 lzb.scene.triangles                 string: the scene's expanded triangle count
// NNNN is the frame number, zero-padded to at least four digits.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/image/reference.hpp"

namespace lzb {

inline constexpr const char* kIdLowChannel = "ID";
inline constexpr const char* kIdHighChannel = "ID.hi";
inline constexpr const char* kBoxColorChannels[3] = {"R.aa", "G.aa", "B.aa"};
std::string subsampleIdLowChannel(int k);   // "sub.ID.k"
std::string subsampleIdHighChannel(int k);  // "sub.ID.hi.k"

// How a frame was made, kept exactly in its EXR header, so that `lzb compare --scene` traces the
// frame's own rays and refuses a reference of another view or another scene.
struct FrameOrigin {
  Camera camera;                // its spec (position, look-at, up, fov, near, far) and size
  uint64_t sceneTriangles = 0;  // Scene::expandedTriangles() of the scene it shows
};

// "frame_0007" for frame 7.
std::string frameStem(int frame);

// Writes dir/frame_NNNN.exr (with the sub-sample channels when `subsamples` is given: fb is then
// the reference's centre render; with the header attributes when `origin` is given, its camera of
// fb's size) then dir/frame_NNNN.png, each through a temporary file + rename. The directory must
// exist (it is not created). Throws InputError naming the file on failure, leaving neither a
// partial file nor a temporary behind.
void writeFrame(const Framebuffer& fb, const std::filesystem::path& dir, int frame,
                const ReferenceFrame* subsamples = nullptr, const FrameOrigin* origin = nullptr);

// Writes only the EXR (plain, or with the sub-sample channels of `subsamples`, same size as fb;
// with the header attributes of `origin`) or only the PNG of fb to `path` (atomically, as
// writeFrame).
void writeExr(const Framebuffer& fb, const std::filesystem::path& path,
              const FrameOrigin* origin = nullptr);
void writeExr(const Framebuffer& fb, const ReferenceFrame& subsamples,
              const std::filesystem::path& path, const FrameOrigin* origin = nullptr);
void writePng(const Framebuffer& fb, const std::filesystem::path& path);

// Reads an EXR written by writeExr back exactly (extra channels are ignored). Throws InputError
// naming the file (and the channel, when one is missing or of the wrong type).
Framebuffer readFrameExr(const std::filesystem::path& path);

// Reads the reference of an EXR that has the sub-sample channels: centre IDs from ID / ID.hi,
// sub-sample IDs and box colour exactly as written. Throws InputError naming the file when they
// are missing (saying to render it with --subsamples) or of the wrong type.
ReferenceFrame readReferenceExr(const std::filesystem::path& path);

// The header attributes of an EXR, exactly as written; nullopt when it has none (written without
// an origin, or by an older lzb). Throws InputError naming the file when only some are there,
// one has the wrong type, the camera is invalid, or its size is not the image's.
std::optional<FrameOrigin> readFrameOrigin(const std::filesystem::path& path);

}  // namespace lzb
