#include "src/scene/ply_stream.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "src/core/error.hpp"
#include "src/scene/mesh_faces.hpp"
#include "src/scene/ply_text_reader.hpp"

namespace lzb {

namespace {

constexpr size_t kHeaderLimit = 1 << 20;  // assimp reads a header in its first 1 MiB block
constexpr size_t kReadBuffer = 1 << 20;
constexpr uint64_t kMaxCount = 0xffffffffu;  // assimp counts elements in 32 bits

}  // namespace

// Buffered reads of a PLY file's binary data, in its byte order; a read past the end is an
// InputError naming the element being read.
class PlyReader {
 public:
  static constexpr bool kBinary = true;

  PlyReader(const std::filesystem::path& path, const std::string& where, uint64_t offset, bool big)
      : where_(where), big_(big), buffer_(kReadBuffer) {
    file_ = std::fopen(path.c_str(), "rb");
    require(file_ != nullptr, where_, "cannot be read (permission?)");
    std::fseek(file_, 0, SEEK_END);
    size_ = uint64_t(std::ftell(file_));
    seek(offset);
  }
  ~PlyReader() { std::fclose(file_); }
  PlyReader(const PlyReader&) = delete;
  PlyReader& operator=(const PlyReader&) = delete;

  // What is being read, for the message when the data ends.
  void at(const std::string* element, uint64_t index, uint64_t count) {
    element_ = element, index_ = index, count_ = count;
  }
  uint64_t offset() const { return start_ + pos_; }
  uint64_t size() const { return size_; }

  double scalar(PlyType t) {
    unsigned char b[8];
    const int n = plyTypeBytes(t);
    bytes(b, size_t(n));
    if (big_) std::reverse(b, b + n);
    switch (t) {
      case PlyType::Int8:
        return double(int8_t(b[0]));
      case PlyType::UInt8:
        return double(b[0]);
      case PlyType::Int16:
        return double(as<int16_t>(b));
      case PlyType::UInt16:
        return double(as<uint16_t>(b));
      case PlyType::Int32:
        return double(as<int32_t>(b));
      case PlyType::UInt32:
        return double(as<uint32_t>(b));
      case PlyType::Float32:
        return double(as<float>(b));
      case PlyType::Float64:
        return as<double>(b);
    }
    return 0.0;
  }
  void skip(PlyType t, uint64_t n) { skip(n * uint64_t(plyTypeBytes(t))); }
  void finish() {}  // what follows the elements is not read
  void skip(uint64_t n) {
    if (n <= len_ - pos_) {
      pos_ += size_t(n);
      return;
    }
    require(n <= size_ - offset(), where_, [this] { return truncated(); });
    seek(offset() + n);
  }
  std::string truncated() const {
    return "truncated: PLY binary data ends inside element '" + *element_ + "' " +
           std::to_string(index_) + " of " + std::to_string(count_);
  }

 private:
  template <class T>
  static T as(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  void seek(uint64_t to) {
    std::fseek(file_, long(to), SEEK_SET);
    start_ = to, pos_ = 0, len_ = 0;
  }
  void bytes(unsigned char* out, size_t n) {
    if (n > len_ - pos_) refill();
    require(n <= len_ - pos_, where_, [this] { return truncated(); });
    std::memcpy(out, buffer_.data() + pos_, n);
    pos_ += n;
  }
  void refill() {
    std::memmove(buffer_.data(), buffer_.data() + pos_, len_ - pos_);
    start_ += pos_, len_ -= pos_, pos_ = 0;
    len_ += std::fread(buffer_.data() + len_, 1, buffer_.size() - len_, file_);
  }

  std::string where_;
  bool big_;
  std::FILE* file_ = nullptr;
  uint64_t size_ = 0, start_ = 0;  // start_: file offset of buffer_[0]
  std::vector<unsigned char> buffer_;
  size_t pos_ = 0, len_ = 0;
  const std::string* element_ = nullptr;
  uint64_t index_ = 0, count_ = 0;
};

// Which elements and properties hold the mesh (indices into the header's lists; -1: none).
struct PlyMeshStream::Layout {
  size_t vertex = 0, face = 0;
  int x = -1, y = -1, z = -1, rgba[4] = {-1, -1, -1, -1};
  int indices = -1;
};

namespace {

using Layout = PlyMeshStream::Layout;

// A vertex property's role as assimp 5.2 names it (the last of a name wins, lists are ignored).
void vertexRole(const PlyProperty& p, int i, Layout& l) {
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

// The layout, or why the file is left to the loader.
std::string layoutOf(const PlyHeader& h, Layout& l, const std::string& where) {
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
    require(e->count <= kMaxCount, where,
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

// A colour component as assimp 5.2 normalises it (PLYImporter::NormalizeColorValue).
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
  const std::string& where = s->where_;
  std::ifstream file(path, std::ios::binary);
  std::string head(kHeaderLimit, '\0');
  file.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(file.gcount()));
  const bool more = file.peek() != std::ifstream::traits_type::eof();
  const size_t end = head.find("end_header");
  if (more && (end == std::string::npos || end + 12 > head.size())) {
    why = "a header longer than 1 MiB";
    return nullptr;
  }
  s->header_ = parsePlyHeader(head, where);
  s->layout_ = std::make_unique<Layout>();
  why = layoutOf(s->header_, *s->layout_, where);
  // assimp drops a data byte 0x0A right after "end_header\n", taking it for half a "\r\n".
  if (why.empty() && s->header_.lfEnd && s->header_.dataStart < head.size() &&
      head[s->header_.dataStart] == '\n')
    why = "a first data byte that the loader takes for a line end";
  if (!why.empty()) return nullptr;
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
  const Layout& l = *layout_;
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
  const Layout& l = *layout_;
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
  const PlyElement& el = header_.elements[layout_->face];
  const size_t indexAt = size_t(layout_->indices);
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
