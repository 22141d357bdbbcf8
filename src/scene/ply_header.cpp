#include "src/scene/ply_header.hpp"

#include <algorithm>
#include <charconv>
#include <sstream>

#include "src/core/error.hpp"

namespace lzb {

namespace {

struct TypeName {
  const char* name;
  PlyType type;
};
constexpr TypeName kTypes[] = {
    {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
    {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
    {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
    {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
    {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
    {"float64", PlyType::Float64}};

bool typeNamed(const std::string& name, PlyType& type) {
  for (const TypeName& t : kTypes)
    if (name == t.name) return type = t.type, true;
  return false;
}

std::vector<std::string> wordsOf(std::string_view line) {
  std::istringstream s{std::string(line)};
  std::vector<std::string> words;
  for (std::string w; s >> w;) words.push_back(w);
  return words;
}

PlyProperty parseProperty(const std::vector<std::string>& w, const std::string& line,
                          const std::string& where) {
  PlyProperty p;
  const auto bad = [&] { return "malformed PLY header line '" + line + "'"; };
  if (w.size() >= 2 && w[1] == "list") {
    require(w.size() == 5, where, bad());
    p.list = true;
    require(typeNamed(w[2], p.countType) && typeNamed(w[3], p.type), where,
            "unknown PLY list type in '" + line + "'");
    require(plyTypeIsInteger(p.countType), where,
            "PLY list count type must be an integer type in '" + line + "'");
    p.name = w[4];
    return p;
  }
  require(w.size() == 3, where, bad());
  require(typeNamed(w[1], p.type), where, "unknown PLY property type in '" + line + "'");
  p.name = w[2];
  return p;
}

PlyElement parseElement(const std::vector<std::string>& w, const std::string& line,
                        const std::string& where) {
  PlyElement e;
  const auto r = w.size() == 3 ? std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count)
                               : std::from_chars_result{nullptr, std::errc::invalid_argument};
  require(r.ec == std::errc() && r.ptr == w[2].data() + w[2].size(), where,
          "malformed PLY header line '" + line + "'");
  e.name = w[1];
  return e;
}

// What assimp 5.2's header reader makes of a line differently from the format, or "".
// It reads "ply" and the format on the first two lines, and ends an element's property list at
// the first other line (a comment, a blank line...), skipping the properties after it.
struct QuirkWatch {
  int lineNo = 0;
  bool inElement = false, propertiesEnded = false;
  std::string quirk;

  void note(const std::string& q) {
    if (quirk.empty()) quirk = q;
  }
  void line(std::string_view raw, const std::vector<std::string>& w) {
    ++lineNo;
    if (std::any_of(raw.begin(), raw.end(),
                    [](char c) { return (unsigned char)c < 0x20 && c != '\t'; }))
      note("a control character in the header");
    if (lineNo == 1 && !(w.size() == 1 && w[0] == "ply")) note("a first line other than 'ply'");
    if (lineNo == 2 && (w.empty() || w[0] != "format")) note("no format on the second line");
    if (lineNo <= 2) return;
    if (w.empty()) return note("a blank header line");
    if (w[0] == "element") {
      inElement = true, propertiesEnded = false;
    } else if (w[0] == "property") {
      if (propertiesEnded) note("a property line after another line inside its element");
    } else {
      if (w[0] == "comment" && w.size() > 1 && w[1] == "TextureFile") note("a TextureFile comment");
      if (w[0] != "comment" && inElement) note("an '" + w[0] + "' line among the elements");
      propertiesEnded = inElement;
    }
  }
};

}  // namespace

int plyTypeBytes(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

bool plyTypeIsInteger(PlyType t) {
  return t != PlyType::Float32 && t != PlyType::Float64;
}

PlyHeader parsePlyHeader(std::string_view bytes, const std::string& where) {
  require(bytes.substr(0, 3) == "ply", where, "not a PLY file (no 'ply' magic)");
  const size_t end = bytes.find("end_header");
  require(end != std::string_view::npos, where,
          "PLY header has no end_header (truncated or malformed)");
  const size_t after = end + 10;
  const bool lf = after < bytes.size() && bytes[after] == '\n';
  const bool crlf = bytes.substr(after, 2) == "\r\n";
  require(bytes[end - 1] == '\n' && (lf || crlf || after == bytes.size()), where,
          "PLY end_header is not on a line of its own");
  require(bytes.substr(0, end).find('\0') == std::string_view::npos, where,
          "PLY header holds a NUL byte");
  PlyHeader h;
  h.lfEnd = lf;
  h.dataStart = after + (crlf ? 2 : lf ? 1 : 0);
  QuirkWatch watch;
  for (size_t at = 0; at < end;) {
    const size_t eol = bytes.find('\n', at);
    std::string_view raw = bytes.substr(at, eol - at);
    at = eol + 1;
    if (!raw.empty() && raw.back() == '\r') raw.remove_suffix(1);
    const std::string line(raw);
    const std::vector<std::string> w = wordsOf(raw);
    watch.line(raw, w);
    if (w.empty()) continue;
    if (w[0] == "format") {
      require(w.size() == 3, where, "malformed PLY header line '" + line + "'");
      h.format = w[1];
    } else if (w[0] == "element") {
      h.elements.push_back(parseElement(w, line, where));
    } else if (w[0] == "property") {
      require(!h.elements.empty(), where, "PLY property before any element");
      h.elements.back().properties.push_back(parseProperty(w, line, where));
    }
  }
  h.quirk = watch.quirk;
  for (const PlyElement& e : h.elements)
    require(e.count == 0 || !e.properties.empty(), where,
            "PLY element '" + e.name + "' has no properties");
  require(std::any_of(h.elements.begin(), h.elements.end(),
                      [](const PlyElement& e) { return e.name == "vertex"; }),
          where, "PLY header declares no 'vertex' element");
  return h;
}

}  // namespace lzb
