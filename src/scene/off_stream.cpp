#include "src/scene/off_stream.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "src/core/error.hpp"
#include "src/scene/text_tokens.hpp"

namespace lzb {

namespace {

constexpr size_t kLineLimit = 4000;  // assimp copies an OFF line into a 4096-byte buffer
constexpr uint64_t kMaxCount = std::numeric_limits<uint32_t>::max();

// A line's content without its line end, or NotStreamed where assimp would split or end it
// elsewhere (a carriage return, form feed or NUL inside, a line longer than its buffer).
std::string_view content(std::string_view line) {
  line = withoutLineEnd(line);
  if (line.find_first_of(std::string_view("\0\r\f", 3)) != std::string_view::npos)
    throw NotStreamed{"a NUL, carriage return or form feed inside a line"};
  if (line.size() > kLineLimit) throw NotStreamed{"a line longer than 4000 characters"};
  return line;
}

bool blank(std::string_view line) {
  return line.find_first_not_of(" \t") == std::string_view::npos;
}

// The next line with content, blank lines skipped (and comment lines where `comments`); false at
// the end of the file.
bool nextLine(TextLines& lines, std::string_view& line, bool comments) {
  for (std::string_view raw; lines.next(raw);) {
    line = content(raw);
    if (line.empty()) continue;  // assimp skips line ends between lines
    if (blank(line)) throw NotStreamed{"a line of only spaces"};
    if (comments && line[line.find_first_not_of(" \t")] == '#') continue;
    return true;
  }
  return false;
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::string_view t; nextToken(line, t);) out.push_back(t);
  return out;
}

uint64_t count(std::string_view token) {
  const std::optional<int64_t> n = assimpInteger(token, false, kMaxCount);
  if (!n) throw NotStreamed{"a count that is not one plain number ('" + std::string(token) + "')"};
  return uint64_t(*n);
}

float real(std::string_view token) {
  const std::optional<double> v = assimpReal(token, false);
  if (!v) throw NotStreamed{"a value that is not one plain number ('" + std::string(token) + "')"};
  return float(*v);
}

}  // namespace

std::unique_ptr<OffMeshStream> OffMeshStream::open(const std::filesystem::path& path,
                                                   std::string& why) {
  std::unique_ptr<OffMeshStream> s(new OffMeshStream(path));
  try {
    TextLines lines(path, s->where_, 0);
    s->readHeader(lines);
    s->readVertices(lines);
    s->faceData_ = lines.offset();
    s->countFaces();
  } catch (const NotStreamed& e) {
    why = "an OFF file with " + e.why;
    return nullptr;
  }
  s->requireTriangles();
  return s;
}

void OffMeshStream::readHeader(TextLines& lines) {
  std::string_view line;
  if (!nextLine(lines, line, true)) throw NotStreamed{"no header"};
  std::vector<std::string_view> w = tokens(line);
  const std::string_view keyword = w[0];
  colours_ = keyword == "COFF" || keyword == "CNOFF";
  normals_ = keyword == "NOFF" || keyword == "CNOFF";
  if (!colours_ && !normals_ && keyword != "OFF")
    throw NotStreamed{"a header other than OFF, COFF, NOFF or CNOFF"};
  if (w.size() == 1) {
    if (!nextLine(lines, line, true)) throw NotStreamed{"no counts"};
    w = tokens(line);
  } else {
    w.erase(w.begin());
  }
  if (w.size() != 3) throw NotStreamed{"a counts line of other than three counts"};
  vertices_ = count(w[0]), faces_ = count(w[1]), count(w[2]);
  if (vertices_ == 0 || faces_ == 0) throw NotStreamed{"no vertices or no faces"};
}

void OffMeshStream::readVertices(TextLines& lines) {
  // assimp reads the colours from where the normals' z starts (it does not move past it), so
  // with both they are nz r g (and b for alpha).
  const size_t colourAt = normals_ ? 5 : 3;
  const size_t values = colourAt + (colours_ ? 4 : normals_ ? 1 : 0);
  held_.positions.resize(size_t(vertices_));
  if (colours_) held_.colours.resize(size_t(vertices_));
  Bounds bounds;
  std::string_view line;
  for (uint64_t v = 0; v < vertices_; ++v) {
    require(nextLine(lines, line, false), where_, [&] {
      return "truncated: the header promises " + std::to_string(vertices_) +
             " vertices, the file has " + std::to_string(v);
    });
    const std::vector<std::string_view> w = tokens(line);
    // assimp reads on past a vertex's values into the next line's only where there are fewer.
    if (w.size() < values) throw NotStreamed{"a vertex line with fewer values than the header's"};
    glm::vec3& p = held_.positions[size_t(v)];
    p = glm::vec3(real(w[0]), real(w[1]), real(w[2]));
    for (size_t k = 3; k < values; ++k) real(w[k]);  // normals: read (a bad one fails the loader)
    if (colours_)
      held_.colours[size_t(v)] =
          glm::vec3(real(w[colourAt]), real(w[colourAt + 1]), real(w[colourAt + 2]));
    const glm::dvec3 d(p);
    if (std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)) bounds.extend(d);
  }
  held_.place(bounds);
}

void OffMeshStream::readFaces(FaceChunks& faces) const {
  TextLines lines(path_, where_, faceData_);
  std::vector<uint32_t> index;
  std::string_view line;
  for (uint64_t f = 0; f < faces_; ++f) {
    require(nextLine(lines, line, false), where_, [&] {
      return "truncated: the header promises " + std::to_string(faces_) + " faces, the file has " +
             std::to_string(f);
    });
    const std::vector<std::string_view> w = tokens(line);
    const uint64_t k = count(w[0]);
    // assimp skips a face of no or more than 9 vertices and clamps an index past the vertices.
    if (k == 0 || k > 9 || w.size() < k + 1)
      throw NotStreamed{"a face of no, more than 9 or missing vertices"};
    index.resize(size_t(k));
    for (size_t i = 0; i < k; ++i) {
      const uint64_t v = count(w[i + 1]);
      if (v >= vertices_) throw NotStreamed{"a face index past the vertices"};
      index[i] = uint32_t(v);
    }
    faces.face(index);
  }
}

}  // namespace lzb
