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
// NNNN is the frame number, zero-padded to at least four digits.
#include <filesystem>
#include <string>

#include "src/core/framebuffer.hpp"

namespace lzb {

inline constexpr const char* kIdLowChannel = "ID";
inline constexpr const char* kIdHighChannel = "ID.hi";

// "frame_0007" for frame 7.
std::string frameStem(int frame);

// Writes dir/frame_NNNN.exr then dir/frame_NNNN.png, each through a temporary file + rename.
// The directory must exist (it is not created). Throws InputError naming the file on failure,
// leaving neither a partial file nor a temporary behind.
void writeFrame(const Framebuffer& fb, const std::filesystem::path& dir, int frame);

// Writes only the EXR or only the PNG of fb to `path` (atomically, as writeFrame).
void writeExr(const Framebuffer& fb, const std::filesystem::path& path);
void writePng(const Framebuffer& fb, const std::filesystem::path& path);

// Reads an EXR written by writeExr back exactly. Throws InputError naming the file (and the
// channel, when one is missing or of the wrong type).
Framebuffer readFrameExr(const std::filesystem::path& path);

}  // namespace lzb
