#include "src/scene/ply_binary.hpp"

#include <fstream>

namespace lzb {

namespace {

constexpr size_t kHeaderLimit = 1 << 20;  // assimp reads a header in its first 1 MiB block
constexpr size_t kHeaderStep = 1 << 16;

// A vertex property's role as assimp 5.2 names it (the last of a name wins, lists are ignored).
void vertexRole(const PlyProperty& p, int i, PlyMeshLayout& l) {
  if (p.list) return;
  const std::string& n = p.name;
  if (n == "x") l.x = i;
  if (n == "y") l.y = i;
  if (n == "z") l.z = i;
  if (n == "red" || n == "r") l.rgba[0] = i;
  if (n == "green" || n == "g") l.rgba[1] = i;
  if (n == "blue" || n == "b") l.rgba[2] = i;
  if (n == "alpha") l.rgba[3] = i;
}

}  // namespace

std::string plyMeshLayout(const PlyHeader& h, PlyMeshLayout& l, const std::string& where) {
  require(
      h.format == "ascii" || h.format == "binary_little_endian" || h.format == "binary_big_endian",
      where, "unknown PLY format '" + h.format + "'");
  if (!h.quirk.empty()) return h.quirk;
  int vertices = 0, faces = 0;
  for (size_t e = 0; e < h.elements.size(); ++e) {
    const std::string& n = h.elements[e].name;
    if (n == "tristrips") return "triangle strips";
    if (n == "vertex") ++vertices, l.vertex = e;
    if (n == "face") ++faces, l.face = e;
  }
  if (vertices != 1 || faces != 1) return "not one 'vertex' and one 'face' element";
  if (l.face < l.vertex) return "faces before the vertices";
  const PlyElement &ve = h.elements[l.vertex], &fe = h.elements[l.face];
  for (const PlyElement* e : {&ve, &fe})
    require(e->count <= kPlyMaxCount, where,
            std::to_string(e->count) + " '" + e->name +
                "' elements, more than the loader reads (2^32 - 1)");
  if (ve.count == 0 || fe.count == 0) return "no vertices or no faces";
  for (size_t i = 0; i < ve.properties.size(); ++i) vertexRole(ve.properties[i], int(i), l);
  if (l.x < 0 || l.y < 0 || l.z < 0) return "a vertex without x, y and z";
  for (size_t i = 0; i < fe.properties.size(); ++i) {
    const PlyProperty& p = fe.properties[i];
    if (p.list && p.name == "texcoord") return "face texture coordinates";
    if (p.list && (p.name == "vertex_index" || p.name == "vertex_indices")) l.indices = int(i);
  }
  if (l.indices < 0) return "no vertex index list in the faces";
  if (!plyTypeIsInteger(fe.properties[size_t(l.indices)].type)) return "non-integer vertex indices";
  return "";
}

float normalisedColour(double v, PlyType t) {
  switch (t) {
    case PlyType::Float32:
    case PlyType::Float64:
      return float(v);
    case PlyType::UInt8:
      return float(uint32_t(v)) / float(0xFF);
    case PlyType::Int8:
      return float(int32_t(v) + 0xFF / 2) / float(0xFF);
    case PlyType::UInt16:
      return float(uint32_t(v)) / float(0xFFFF);
    case PlyType::Int16:
      return float(int32_t(v) + 0xFFFF / 2) / float(0xFFFF);
    case PlyType::UInt32:
      return float(uint32_t(v)) / float(0xFFFF);
    case PlyType::Int32:
      return float(int32_t(v)) / float(0xFF) + 0.5f;
  }
  return 0.0f;
}

PlyHead readPlyHead(const std::filesystem::path& path, const std::string& where, std::string& why) {
  PlyHead head;
  std::ifstream file(path, std::ios::binary);
  std::string bytes;
  size_t end = std::string::npos;
  // In steps, so a rank reading a slice reads little more than the header.
  while (bytes.size() < kHeaderLimit) {
    const size_t had = bytes.size();
    bytes.resize(std::min(kHeaderLimit, had + kHeaderStep));
    file.read(bytes.data() + had, std::streamsize(bytes.size() - had));
    bytes.resize(had + size_t(file.gcount()));
    end = bytes.find("end_header");
    if ((end != std::string::npos && end + 12 <= bytes.size()) || bytes.size() == had) break;
  }
  head.bytesRead = bytes.size();
  const bool more = file.peek() != std::ifstream::traits_type::eof();
  if (more && (end == std::string::npos || end + 12 > bytes.size())) {
    why = "a header longer than 1 MiB";
    return head;
  }
  head.header = parsePlyHeader(bytes, where);
  why = plyMeshLayout(head.header, head.layout, where);
  // assimp drops a data byte 0x0A right after "end_header\n", taking it for half a "\r\n".
  if (why.empty() && head.header.lfEnd && head.header.dataStart < bytes.size() &&
      bytes[head.header.dataStart] == '\n')
    why = "a first data byte that the loader takes for a line end";
  return head;
}

}  // namespace lzb
