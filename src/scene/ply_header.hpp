#pragma once
// The header of a PLY file, parsed for the streaming reader (ply_stream.hpp): elements, their
// properties with types, where the data starts, and whether the loader (assimp 5.2) would read
// the header differently from the PLY format, which the streaming reader then leaves to it.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lzb {

enum class PlyType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

int plyTypeBytes(PlyType t);
bool plyTypeIsInteger(PlyType t);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // of the scalar, or of a list's items
  bool list = false;
  PlyType countType = PlyType::UInt8;  // lists: of the count
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  std::string format;  // ascii, binary_little_endian or binary_big_endian
  std::vector<PlyElement> elements;
  uint64_t dataStart = 0;  // bytes from the file's start
  bool lfEnd = false;      // end_header ends in "\n" alone (not "\r\n")
  std::string quirk;       // non-empty: how assimp 5.2 would read this header otherwise
};

// Parses the header at the start of `bytes` (the file's first bytes, at least up to the line
// after end_header). Throws InputError naming `where` for what the loader's file check refuses:
// no end_header, one not on a line of its own, a NUL, malformed element or property lines,
// unknown types, non-integer list counts, elements without properties, no vertex element.
PlyHeader parsePlyHeader(std::string_view bytes, const std::string& where);

}  // namespace lzb
