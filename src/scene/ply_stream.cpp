#include "src/scene/ply_stream.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "src/core/error.hpp"
#include "src/scene/mesh_faces.hpp"
#include "src/scene/ply_binary.hpp"
#include "src/scene/ply_text_reader.hpp"

namespace lzb {

namespace {

// A list's count (signed counts must not be negative).
template <class Reader>
uint64_t listCount(Reader& in, const PlyProperty& p, const std::string& where, uint64_t i) {
  const double n = in.scalar(p.countType);
  require(n >= 0.0, where, [&] {
    return "malformed: PLY list '" + p.name + "' of element " + std::to_string(i) +
           " has a negative count";
  });
  return uint64_t(n);
}

template <class Reader>
void skipProperty(Reader& in, const PlyProperty& p, const std::string& where, uint64_t i) {
  in.skip(p.type, p.list ? listCount(in, p, where, i) : 1);
}

// An element of fixed size skipped in one seek.
void skipFixed(PlyReader& in, const PlyElement& e, const std::string& where) {
  uint64_t stride = 0;
  for (const PlyProperty& p : e.properties) stride += uint64_t(plyTypeBytes(p.type));
  in.at(&e.name, 0, e.count);
  require(stride == 0 || e.count <= (in.size() - in.offset()) / stride, where,
          "truncated: PLY binary data too short for " + std::to_string(e.count) + " '" + e.name +
              "' elements");
  in.skip(stride * e.count);
}

template <class Reader>
void skipElement(Reader& in, const PlyElement& e, const std::string& where) {
  if constexpr (Reader::kBinary)
    if (std::none_of(e.properties.begin(), e.properties.end(),
                     [](const PlyProperty& p) { return p.list; }))
      return skipFixed(in, e, where);
  for (uint64_t i = 0; i < e.count; ++i) {
    in.at(&e.name, i, e.count);
    for (const PlyProperty& p : e.properties) skipProperty(in, p, where, i);
  }
}

}  // namespace

PlyMeshStream::PlyMeshStream(const std::filesystem::path& path) : MeshStream(path) {}

PlyMeshStream::~PlyMeshStream() = default;

std::unique_ptr<PlyMeshStream> PlyMeshStream::open(const std::filesystem::path& path,
                                                   std::string& why) {
  std::unique_ptr<PlyMeshStream> s(new PlyMeshStream(path));
  PlyHead head = readPlyHead(path, s->where_, why);
  if (!why.empty()) return nullptr;
  s->header_ = std::move(head.header);
  s->layout_ = head.layout;
  try {
    s->binary() ? s->scan<PlyReader>() : s->scan<PlyTextReader>();
  } catch (const NotStreamed& e) {
    why = "an ASCII PLY with " + e.why;
    return nullptr;
  }
  return s;
}

template <>
PlyReader PlyMeshStream::reader(uint64_t offset) const {
  return PlyReader(path_, where_, offset, header_.format == "binary_big_endian");
}

template <>
PlyTextReader PlyMeshStream::reader(uint64_t offset) const {
  return PlyTextReader(path_, where_, offset);
}

// The first reading: every element in order, vertices kept, faces checked and counted.
template <class Reader>
void PlyMeshStream::scan() {
  Reader in = reader<Reader>(header_.dataStart);
  const PlyMeshLayout& l = layout_;
  for (size_t e = 0; e < header_.elements.size(); ++e) {
    const PlyElement& el = header_.elements[e];
    if (e == l.vertex) {
      readVertices(in, el);
    } else if (e == l.face) {
      faceData_ = in.offset();
      FaceChunks faces(held_, boundStored_, size_t(1) << 16);
      readFaceElement(in, faces);
      stats_ = faces.finish();
    } else {
      skipElement(in, el, where_);
    }
  }
  in.finish();
  requireTriangles();
}

template <class Reader>
void PlyMeshStream::readVertices(Reader& in, const PlyElement& el) {
  const PlyMeshLayout& l = layout_;
  const bool coloured = std::any_of(l.rgba, l.rgba + 4, [](int i) { return i >= 0; });
  held_.positions.resize(size_t(el.count));
  if (coloured) held_.colours.assign(size_t(el.count), glm::vec3(0.0f));
  std::vector<double> values(el.properties.size());
  Bounds bounds;
  for (uint64_t i = 0; i < el.count; ++i) {
    in.at(&el.name, i, el.count);
    for (size_t k = 0; k < el.properties.size(); ++k) {
      const PlyProperty& p = el.properties[k];
      if (p.list)
        skipProperty(in, p, where_, i);
      else
        values[k] = in.scalar(p.type);
    }
    glm::vec3& v = held_.positions[size_t(i)];
    v = glm::vec3(float(values[size_t(l.x)]), float(values[size_t(l.y)]),
                  float(values[size_t(l.z)]));
    for (int c = 0; coloured && c < 3; ++c)
      if (l.rgba[c] >= 0)
        held_.colours[size_t(i)][c] =
            normalisedColour(values[size_t(l.rgba[c])], el.properties[size_t(l.rgba[c])].type);
    const glm::dvec3 p = storedVertex(glm::dmat4(1.0), v.x, v.y, v.z, glm::dvec3(0.0));
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) bounds.extend(p);
  }
  held_.place(bounds);
}

template <class Reader>
void PlyMeshStream::readFaceElement(Reader& in, FaceChunks& faces) const {
  const PlyElement& el = header_.elements[layout_.face];
  const size_t indexAt = size_t(layout_.indices);
  const uint64_t vertices = held_.positions.size();
  std::vector<uint32_t> index;
  for (uint64_t f = 0; f < el.count; ++f) {
    in.at(&el.name, f, el.count);
    for (size_t k = 0; k < el.properties.size(); ++k) {
      const PlyProperty& p = el.properties[k];
      if (k != indexAt) {
        skipProperty(in, p, where_, f);
        continue;
      }
      const uint64_t n = listCount(in, p, where_, f);
      require(n > 0, where_, [&] {
        return "malformed or truncated: face " + std::to_string(f) + " has no vertices";
      });
      index.resize(size_t(n));
      for (uint32_t& i : index) {
        const double v = in.scalar(p.type);
        i = uint32_t(int64_t(v));  // as assimp converts: a negative index wraps, out of range
        require(i < vertices, where_, [&] {
          return "malformed: face " + std::to_string(f) + " uses vertex " + std::to_string(i) +
                 " of " + std::to_string(vertices);
        });
      }
    }
    faces.face(index);
  }
}

void PlyMeshStream::readFaces(FaceChunks& faces) const {
  if (binary()) {
    PlyReader in = reader<PlyReader>(faceData_);
    readFaceElement(in, faces);
  } else {
    PlyTextReader in = reader<PlyTextReader>(faceData_);
    readFaceElement(in, faces);
  }
}

}  // namespace lzb
