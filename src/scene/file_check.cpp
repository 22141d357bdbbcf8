#include "src/scene/file_check.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/core/whole_file.hpp"
#include "src/scene/ply_header.hpp"

namespace lzb {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// Whitespace-separated tokens of a memory buffer, without copying.
class Tokens {
 public:
  Tokens(const std::string& text, size_t from) : s_(text), at_(from) {}
  bool next(std::string_view& token) {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
    if (at_ >= s_.size()) return false;
    const size_t start = at_;
    while (at_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
    token = std::string_view(s_).substr(start, at_ - start);
    return true;
  }

 private:
  const std::string& s_;
  size_t at_;
};

// ---- PLY ----

uint64_t readUnsigned(const unsigned char* p, int size, bool bigEndian) {
  uint64_t v = 0;
  for (int i = 0; i < size; ++i) v |= uint64_t(p[bigEndian ? size - 1 - i : i]) << (8 * i);
  return v;
}

void checkPly(const std::filesystem::path& path, const std::string& data) {
  const std::string where = path.string();
  // The header's rules (end_header on a line of its own, no NUL, known types...): ply_header.hpp.
  const PlyHeader header = parsePlyHeader(data, where);
  const std::vector<PlyElement>& elements = header.elements;
  const std::string& format = header.format;
  const uint64_t dataStart = header.dataStart;
  if (format == "ascii") {
    // One token per scalar; a list is its count followed by that many items.
    Tokens tokens(data, dataStart);
    std::string_view t;
    for (const PlyElement& e : elements)
      for (uint64_t i = 0; i < e.count; ++i)
        for (const PlyProperty& p : e.properties) {
          require(tokens.next(t), where, [&] {
            return "truncated: PLY data ends inside element '" + e.name + "' " + std::to_string(i) +
                   " of " + std::to_string(e.count);
          });
          if (!p.list) continue;
          uint64_t items = 0;
          const auto r = std::from_chars(t.data(), t.data() + t.size(), items);
          require(r.ec == std::errc() && r.ptr == t.data() + t.size(), where, [&] {
            return "malformed PLY list count '" + std::string(t) + "' in element '" + e.name + "'";
          });
          for (uint64_t k = 0; k < items; ++k)
            require(tokens.next(t), where, [&] {
              return "truncated: PLY data ends inside element '" + e.name + "' " +
                     std::to_string(i);
            });
        }
    return;
  }
  require(format == "binary_little_endian" || format == "binary_big_endian", where,
          "unknown PLY format '" + format + "'");
  const bool big = format == "binary_big_endian";
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  uint64_t at = dataStart;
  const uint64_t end = data.size();
  for (const PlyElement& e : elements) {
    const bool fixed = std::none_of(e.properties.begin(), e.properties.end(),
                                    [](const PlyProperty& p) { return p.list; });
    if (fixed) {
      uint64_t stride = 0;
      for (const PlyProperty& p : e.properties) stride += uint64_t(plyTypeBytes(p.type));
      require(stride == 0 || e.count <= (end - at) / stride, where,
              "truncated: PLY binary data too short for " + std::to_string(e.count) + " '" +
                  e.name + "' elements");
      at += stride * e.count;
      continue;
    }
    for (uint64_t i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        const auto need = [&](uint64_t n) {
          require(n <= end - at, where, [&] {
            return "truncated: PLY binary data ends inside element '" + e.name + "' " +
                   std::to_string(i) + " of " + std::to_string(e.count);
          });
        };
        const uint64_t size = uint64_t(plyTypeBytes(p.type));
        if (!p.list) {
          need(size);
          at += size;
          continue;
        }
        const int countSize = plyTypeBytes(p.countType);
        need(uint64_t(countSize));
        const uint64_t items = readUnsigned(bytes + at, countSize, big);
        at += uint64_t(countSize);
        // Divided, not multiplied: a count near 2^32 must not wrap.
        require(items <= (end - at) / size, where, [&] {
          return "truncated: PLY binary data ends inside element '" + e.name + "' " +
                 std::to_string(i) + " of " + std::to_string(e.count);
        });
        at += items * size;
      }
  }
}

// ---- OFF ----

// The header keywords assimp reads: [ST][C][N][4]OFF (nOFF, of any dimension, it misreads).
bool offKeyword(std::string_view w) {
  for (std::string_view prefix : {"ST", "C", "N", "4"})
    if (w.substr(0, prefix.size()) == prefix) w.remove_prefix(prefix.size());
  return w == "OFF";
}

void checkOff(const std::filesystem::path& path, const std::string& data) {
  const std::string where = path.string();
  std::istringstream in(data);
  std::string line;
  bool body = false;  // past the counts: assimp reads a comment line there as a vertex or face
  // Lines without comments and blanks, split into words.
  const auto nextLine = [&](std::vector<std::string>& words) {
    while (std::getline(in, line)) {
      require(!body || line.find_first_not_of(" \t\r") == std::string::npos ||
                  line[line.find_first_not_of(" \t\r")] != '#',
              where,
              [&] { return "a comment line among the OFF vertices or faces: '" + line + "'"; });
      line = line.substr(0, line.find('#'));
      std::istringstream s(line);
      words.clear();
      for (std::string w; s >> w;) words.push_back(w);
      if (!words.empty()) return true;
    }
    return false;
  };
  std::vector<std::string> words;
  require(nextLine(words), where, "empty OFF file");
  // The header keyword may carry prefixes (COFF, NOFF, STOFF...) and the counts on the same line.
  if (words[0].find("OFF") != std::string::npos) {
    // Counts read after another keyword ("OFF4 4 0") would not be the counts assimp reads.
    require(offKeyword(words[0]), where, "malformed OFF header keyword '" + words[0] + "'");
    if (words.size() > 1 && lower(words[1]) == "binary") return;  // binary OFF: left to assimp
    words.erase(words.begin());
    if (words.empty()) require(nextLine(words), where, "truncated: OFF file has no counts line");
  }
  uint64_t counts[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    require(size_t(i) < words.size(), where, "malformed OFF counts line");
    const std::string& w = words[size_t(i)];
    const auto r = std::from_chars(w.data(), w.data() + w.size(), counts[i]);
    require(r.ec == std::errc() && r.ptr == w.data() + w.size(), where,
            "malformed OFF counts line: '" + w + "' is not a count");
  }
  body = true;
  for (uint64_t v = 0; v < counts[0]; ++v)
    require(nextLine(words), where, [&] {
      return "truncated: the header promises " + std::to_string(counts[0]) +
             " vertices, the file has " + std::to_string(v);
    });
  for (uint64_t f = 0; f < counts[1]; ++f) {
    require(nextLine(words), where, [&] {
      return "truncated: the header promises " + std::to_string(counts[1]) +
             " faces, the file has " + std::to_string(f);
    });
    uint64_t k = 0;
    const auto r = std::from_chars(words[0].data(), words[0].data() + words[0].size(), k);
    // k < size, not size >= k + 1: a face size near 2^64 must not wrap.
    require(r.ec == std::errc() && k < words.size(), where,
            [&] { return "malformed OFF face " + std::to_string(f) + ": '" + line + "'"; });
    // assimp's OFF reader crashes on a face of no vertices and drops one of more than 9.
    require(k > 0, where,
            [&] { return "malformed OFF face " + std::to_string(f) + ": it has no vertices"; });
    require(k <= 9, where, [&] {
      return "OFF face " + std::to_string(f) + " has " + std::to_string(k) +
             " vertices; the reader (assimp) takes at most 9";
    });
    // assimp clamps an index past the vertices to the last vertex, silently.
    for (uint64_t i = 1; i <= k; ++i) {
      uint64_t index = 0;
      const std::string& w = words[size_t(i)];
      const auto ri = std::from_chars(w.data(), w.data() + w.size(), index);
      require(ri.ec == std::errc() && ri.ptr == w.data() + w.size() && index < counts[0], where,
              [&] {
                return "malformed OFF face " + std::to_string(f) + ": vertex index '" + w +
                       "' is not one of the " + std::to_string(counts[0]) + " vertices";
              });
    }
  }
}

// ---- STL ----

void checkStl(const std::filesystem::path& path, const std::string& data) {
  const std::string where = path.string();
  if (data.size() >= 84) {
    const uint64_t n =
        readUnsigned(reinterpret_cast<const unsigned char*>(data.data()) + 80, 4, false);
    if (84 + 50 * n == data.size()) return;  // a complete binary STL
  }
  const size_t first = data.find_first_not_of(" \t\r\n");
  const bool ascii = first != std::string::npos && lower(data.substr(first, 5)) == "solid" &&
                     std::none_of(data.begin(), data.end(), [](char c) { return c == '\0'; });
  if (ascii) {
    // The last solid of a complete file closes near its end.
    const std::string tail = lower(data.substr(data.size() - std::min<size_t>(data.size(), 4096)));
    require(tail.find("endsolid") != std::string::npos, where,
            "truncated: ASCII STL has no 'endsolid'");
    return;
  }
  require(data.size() >= 84, where,
          "truncated or malformed STL (" + std::to_string(data.size()) +
              " bytes, shorter than a binary STL header)");
  const uint64_t n =
      readUnsigned(reinterpret_cast<const unsigned char*>(data.data()) + 80, 4, false);
  throw InputError(where + ": truncated or malformed binary STL: header promises " +
                   std::to_string(n) + " triangles (" + std::to_string(84 + 50 * n) +
                   " bytes), file has " + std::to_string(data.size()) + " bytes");
}

// ---- GLB ----

// The binary glTF container: its lengths must lie inside the file (assimp allocates what a
// chunk header claims before reading it: 1.6 GB for a 200-byte file).
void checkGlb(const std::filesystem::path& path, const std::string& data) {
  const std::string where = path.string();
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  require(data.size() >= 12 && data.compare(0, 4, "glTF") == 0, where,
          "not a binary glTF file (no 12-byte GLB header)");
  const uint64_t version = readUnsigned(bytes + 4, 4, false);
  if (version == 1) {  // glTF 1.0: scene content after 20 bytes (its total length is often off)
    require(data.size() >= 20 && readUnsigned(bytes + 12, 4, false) <= data.size() - 20, where,
            "truncated: the GLB scene content runs past the end of the file");
    return;
  }
  require(version == 2, where, "unknown GLB version " + std::to_string(version));
  const uint64_t length = readUnsigned(bytes + 8, 4, false);
  require(length <= data.size(), where,
          "truncated: the GLB header promises " + std::to_string(length) + " bytes, the file has " +
              std::to_string(data.size()));
  // A GLB without its JSON chunk first is one assimp's glTF reader declines, and then every
  // other reader tries the bytes (one read past them).
  require(length >= 20 && data.compare(16, 4, "JSON") == 0, where,
          "malformed GLB: its first chunk is not the JSON chunk");
  for (uint64_t at = 12; at < length;) {
    require(length - at >= 8, where, "truncated: a GLB chunk header runs past the file's length");
    const uint64_t chunk = readUnsigned(bytes + at, 4, false);
    require(chunk <= length - at - 8, where,
            "truncated: a GLB chunk of " + std::to_string(chunk) + " bytes runs past the file's length");
    at += 8 + chunk;
  }
}

}  // namespace

void checkMeshFileComplete(const std::filesystem::path& path) {
  const std::string ext = lower(path.extension().string());
  if (ext != ".ply" && ext != ".off" && ext != ".stl" && ext != ".glb") return;
  const std::string data = readWholeFile(path);
  if (ext == ".ply") {
    require(data.compare(0, 3, "ply") == 0, path.string(), "not a PLY file (no 'ply' magic)");
    checkPly(path, data);
  } else if (ext == ".off") {
    checkOff(path, data);
  } else if (ext == ".glb") {
    checkGlb(path, data);
  } else {
    checkStl(path, data);
  }
}

}  // namespace lzb
