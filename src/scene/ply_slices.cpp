#include "src/scene/ply_slices.hpp"

#include <algorithm>

namespace lzb {

namespace {

// An element's record size, or 0 when it holds a list (its records vary in size).
uint64_t fixedStride(const PlyElement& e) {
  uint64_t stride = 0;
  for (const PlyProperty& p : e.properties) {
    if (p.list) return 0;
    stride += uint64_t(plyTypeBytes(p.type));
  }
  return stride;
}

}  // namespace

PlySlices::PlySlices(const std::filesystem::path& path) : path_(path), where_(path.string()) {}

bool PlySlices::coloured() const {
  return std::any_of(layout_.rgba, layout_.rgba + 4, [](int i) { return i >= 0; });
}

PlyReader PlySlices::reader(uint64_t offset, uint64_t end) const {
  return PlyReader(path_, where_, offset, header_.format == "binary_big_endian", end);
}

std::unique_ptr<PlySlices> PlySlices::open(const std::filesystem::path& path, std::string& why) {
  std::unique_ptr<PlySlices> s(new PlySlices(path));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    why = "not a regular file";  // the stream says which way, as the loader does
    return nullptr;
  }
  PlyHead head = readPlyHead(path, s->where_, why);
  s->bytesRead_ = head.bytesRead;
  if (!why.empty()) return nullptr;
  s->header_ = std::move(head.header);
  s->layout_ = head.layout;
  const PlyHeader& h = s->header_;
  if (h.format == "ascii") {
    why = "ASCII";
    return nullptr;
  }
  // The offsets of the vertex and face elements: every element before the faces fixed in size.
  uint64_t offset = h.dataStart;
  for (size_t e = 0; e < s->layout_.face; ++e) {
    const uint64_t stride = fixedStride(h.elements[e]);
    if (stride == 0) {
      why = "element '" + h.elements[e].name + "' of records of varying size before the faces";
      return nullptr;
    }
    if (e == s->layout_.vertex) s->vertexData_ = offset, s->vertexStride_ = stride;
    offset += stride * h.elements[e].count;
  }
  s->faceData_ = offset;
  // A face record of a triangle: the scalars, the index list's count and three indices.
  const PlyElement& faces = h.elements[s->layout_.face];
  for (size_t k = 0; k < faces.properties.size(); ++k) {
    const PlyProperty& p = faces.properties[k];
    if (int(k) == s->layout_.indices) {
      s->indexAt_ = s->faceStride_;
      s->faceStride_ += uint64_t(plyTypeBytes(p.countType) + 3 * plyTypeBytes(p.type));
    } else if (p.list) {
      why = "a face list besides the vertex indices";
      return nullptr;
    } else {
      s->faceStride_ += uint64_t(plyTypeBytes(p.type));
    }
  }
  s->vertices_ = h.elements[s->layout_.vertex].count;
  s->faces_ = faces.count;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || (size - std::min(size, s->faceData_)) / s->faceStride_ < s->faces_) {
    why = "data shorter than its faces as triangles";
    return nullptr;
  }
  return s;
}

void PlySlices::readVertices(uint64_t begin, uint64_t end, std::vector<glm::vec3>& positions,
                             std::vector<glm::vec3>& colours) {
  const PlyElement& el = header_.elements[layout_.vertex];
  const PlyMeshLayout& l = layout_;
  PlyReader in = reader(vertexData_ + begin * vertexStride_, vertexData_ + end * vertexStride_);
  positions.resize(size_t(end - begin));
  colours.assign(coloured() ? size_t(end - begin) : 0, glm::vec3(0.0f));
  std::vector<double> values(el.properties.size());
  for (uint64_t i = begin; i < end; ++i) {
    in.at(&el.name, i, el.count);
    for (size_t k = 0; k < el.properties.size(); ++k) values[k] = in.scalar(el.properties[k].type);
    positions[size_t(i - begin)] = glm::vec3(float(values[size_t(l.x)]), float(values[size_t(l.y)]),
                                             float(values[size_t(l.z)]));
    for (int c = 0; !colours.empty() && c < 3; ++c)
      if (l.rgba[c] >= 0)
        colours[size_t(i - begin)][c] =
            normalisedColour(values[size_t(l.rgba[c])], el.properties[size_t(l.rgba[c])].type);
  }
  bytesRead_ += in.bytesRead();
}

PlySlices::FaceRead PlySlices::readFaces(uint64_t begin, uint64_t end,
                                         std::vector<uint32_t>& indices) {
  const PlyElement& el = header_.elements[layout_.face];
  const PlyProperty& list = el.properties[size_t(layout_.indices)];
  const uint64_t after = faceStride_ - indexAt_ - uint64_t(plyTypeBytes(list.countType)) -
                         3 * uint64_t(plyTypeBytes(list.type));
  PlyReader in = reader(faceData_ + begin * faceStride_, faceData_ + end * faceStride_);
  const auto stop = [&](FaceRead read) {
    bytesRead_ += in.bytesRead();
    return read;
  };
  indices.reserve(indices.size() + 3 * size_t(end - begin));
  for (uint64_t f = begin; f < end; ++f) {
    in.at(&el.name, f, el.count);
    in.skip(indexAt_);
    if (in.scalar(list.countType) != 3.0) return stop({f, true, ""});
    uint32_t corner[3];
    for (uint32_t& i : corner) i = uint32_t(int64_t(in.scalar(list.type)));  // as the stream does
    for (const uint32_t i : corner)
      if (i >= vertices_)
        return stop({f, false,
                     "malformed: face " + std::to_string(f) + " uses vertex " + std::to_string(i) +
                         " of " + std::to_string(vertices_)});
    indices.insert(indices.end(), corner, corner + 3);
    in.skip(after);
  }
  return stop({end, false, ""});
}

}  // namespace lzb
