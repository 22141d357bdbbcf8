#include "src/scene/obj_stream.hpp"

#include <cmath>
#include <optional>
#include <vector>

#include "src/core/error.hpp"

namespace lzb {

namespace {

constexpr uint64_t kMaxCorners = 0x7fffffff;  // assimp's AI_MAX_VERTICES for one mesh
constexpr uint64_t kObjMinSize = 16;          // assimp refuses a smaller file

bool isSpace(char c) {
  return c == ' ' || c == '\t';
}

// A line's content without its line end, or NotStreamed where assimp would split or join it
// elsewhere (a carriage return, form feed or NUL inside, a continuation backslash).
std::string_view content(std::string_view line) {
  line = withoutLineEnd(line);
  if (line.find_first_of(std::string_view("\0\r\f\\", 4)) != std::string_view::npos)
    throw NotStreamed{"a NUL, carriage return, form feed or backslash inside a line"};
  return line;
}

// The statement keyword of a line ("" for a blank or comment line): its characters up to the
// first space or tab.
std::string_view keyword(std::string_view line) {
  if (line.find_first_not_of(" \t") == std::string_view::npos || line[0] == '#') return {};
  // assimp takes a line by its first character: one indented would be skipped.
  if (isSpace(line[0])) throw NotStreamed{"an indented statement"};
  return line.substr(0, std::min(line.find_first_of(" \t"), line.size()));
}

// A plainly written index as assimp's atoi and digit count read it: [-]d..d, no leading zero,
// at most 9 digits, not 0.
std::optional<int64_t> plainIndex(std::string_view t) {
  const std::string_view digits = !t.empty() && t[0] == '-' ? t.substr(1) : t;
  if (digits.empty() || digits[0] < '1' || digits[0] > '9') return std::nullopt;
  return assimpInteger(t, true, 999999999);
}

// The vertex index of a face corner (v, v/t, v/t/n or v//n) as written, or NotStreamed.
int64_t cornerVertex(std::string_view corner) {
  std::string_view part[3];
  int parts = 0;
  for (size_t at = 0; parts < 3; ++parts) {
    const size_t slash = corner.find('/', at);
    part[parts] = corner.substr(at, slash == std::string_view::npos ? slash : slash - at);
    if (slash == std::string_view::npos) {
      ++parts;
      break;
    }
    at = slash + 1;
    if (parts == 2) throw NotStreamed{"a face corner of more than three parts"};
  }
  for (int p = 0; p < parts; ++p)
    if (!(p == 1 && parts == 3 && part[p].empty()) && !plainIndex(part[p]))
      throw NotStreamed{"a face corner that is not plainly written ('" + std::string(corner) +
                        "')"};
  return *plainIndex(part[0]);
}

// A line's values after its keyword, each a number assimp counts as one (it starts with a digit
// or sign, or is nan or inf) and reads whole.
std::vector<float> values(std::string_view rest) {
  std::vector<float> out;
  for (std::string_view t; nextToken(rest, t);) {
    const bool counted = t[0] == '-' || t[0] == '+' || (t[0] >= '0' && t[0] <= '9') ||
                         t.substr(0, 3) == "nan" || t.substr(0, 3) == "inf";
    const std::optional<double> v = assimpReal(t, false);
    if (!counted || !v)
      throw NotStreamed{"a value that is not one plain number ('" + std::string(t) + "')"};
    out.push_back(float(*v));
  }
  return out;
}

}  // namespace

std::unique_ptr<ObjMeshStream> ObjMeshStream::open(const std::filesystem::path& path,
                                                   std::string& why) {
  std::unique_ptr<ObjMeshStream> s(new ObjMeshStream(path));
  try {
    if (std::filesystem::file_size(path) < kObjMinSize) throw NotStreamed{"under 16 bytes"};
    s->scan();
    s->countFaces();
  } catch (const NotStreamed& e) {
    why = "an OBJ file with " + e.why;
    return nullptr;
  }
  s->requireTriangles();
  return s;
}

void ObjMeshStream::scan() {
  TextLines lines(path_, where_, 0);
  Bounds bounds;
  bool faces = false;
  uint64_t corners = 0;
  for (std::string_view raw; lines.next(raw);) {
    const uint64_t offset = lines.offset() - raw.size();
    const std::string_view line = content(raw);
    const std::string_view key = keyword(line);
    std::string_view rest = line.substr(key.size());
    if (key == "vn" || key == "vt") {
      // Read, never used: assimp fails on a bad one (or on a texture coordinate of 1 or 4).
      const size_t n = values(rest).size();
      if (key == "vn" ? n != 3 : n != 2 && n != 3)
        throw NotStreamed{"a normal or texture coordinate of another size"};
    } else if (key.empty() || key == "s") {
      continue;
    } else if (key == "v") {
      readVertex(rest, bounds);
    } else if (key == "o" || key == "g") {
      if (faces) throw NotStreamed{"an object or group after the first face"};
    } else if (key == "f") {
      if (!faces) faceData_ = offset, verticesBefore_ = held_.positions.size();
      faces = true;
      std::string_view corner;
      if (!nextToken(rest, corner)) throw NotStreamed{"a face without corners"};
      do {
        cornerVertex(corner);
        if (++corners > kMaxCorners) throw NotStreamed{"more face corners than assimp takes"};
      } while (nextToken(rest, corner));
    } else {
      throw NotStreamed{"a '" + std::string(key) + "' statement"};
    }
  }
  if (!faces) throw NotStreamed{"no faces"};
  held_.place(bounds);
}

void ObjMeshStream::readVertex(std::string_view rest, Bounds& bounds) {
  const std::vector<float> v = values(rest);
  const bool coloured = v.size() == 6;
  if (v.size() != 3 && !coloured) throw NotStreamed{"a vertex of other than 3 or 6 values"};
  if (!held_.positions.empty() && coloured != !held_.colours.empty())
    throw NotStreamed{"vertices with and without colours"};
  held_.positions.emplace_back(v[0], v[1], v[2]);
  if (coloured) held_.colours.emplace_back(v[3], v[4], v[5]);
  const glm::dvec3 d(held_.positions.back());
  if (std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)) bounds.extend(d);
}

void ObjMeshStream::readFaces(FaceChunks& faces) const {
  TextLines lines(path_, where_, faceData_);
  int64_t seen = int64_t(verticesBefore_);  // `v` lines so far: a negative index counts back
  const int64_t vertices = int64_t(held_.positions.size());
  std::vector<uint32_t> index;
  for (std::string_view raw; lines.next(raw);) {
    const std::string_view line = content(raw);
    const std::string_view key = keyword(line);
    if (key == "v") ++seen;
    if (key != "f") continue;
    index.clear();
    std::string_view rest = line.substr(1), corner;
    while (nextToken(rest, corner)) {
      const int64_t i = cornerVertex(corner);
      const int64_t v = i > 0 ? i - 1 : seen + i;
      // assimp refuses the file then ("OBJ: vertex index out of range").
      if (v < 0 || v >= vertices) throw NotStreamed{"a face index past the vertices"};
      index.push_back(uint32_t(v));
    }
    faces.face(index);
  }
}

}  // namespace lzb
