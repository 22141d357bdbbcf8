#include "src/scene/toml_scene.hpp"

#include <toml++/toml.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <initializer_list>
#include <iterator>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "src/core/error.hpp"
#include "src/scene/builtin.hpp"
#include "src/scene/mesh_file.hpp"
#include "src/scene/mesh_stream.hpp"
#include "src/scene/toml_text_check.hpp"

namespace lzb {

namespace {

constexpr int64_t kMaxImageSide = 16384;

const char* typeName(toml::node_type t) {
  switch (t) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::string sub(const std::string& prefix, std::string_view key) {
  return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
}
std::string item(const std::string& prefix, size_t i) {
  return prefix + "[" + std::to_string(i) + "]";
}

// A deferred node's triangles: one pass over them, chunk by chunk, as the loaded node holds them.
using DeferredChunks = std::function<void(const std::function<void(const Mesh&)>&)>;

class TomlSceneReader {
 public:
  // deferred: where streamed files and generators go, their nodes deferred (nullptr: every one
  // loaded); deferProcedural: terrain and displaced too (their nodes then lose the definition
  // that sqrt5 samples).
  TomlSceneReader(const std::filesystem::path& path, std::map<uint32_t, DeferredChunks>* deferred,
                  bool deferProcedural = false)
      : path_(path),
        file_(path.string()),
        dir_(path.parent_path()),
        deferred_(deferred),
        deferProcedural_(deferProcedural) {}

  Scene read();

 private:
  enum class Kind { kMesh, kGenerator, kNode };
  struct Entry {
    Kind kind;
    uint32_t node;  // scene node
    size_t index;   // position in its TOML array
    std::optional<CameraSpec> camera;
  };

  [[noreturn]] void fail(const toml::node& at, const std::string& field,
                         const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(at.source().begin.line) + ": " + field + ": " +
                     what);
  }
  const toml::node& need(const toml::table& t, std::string_view key,
                         const std::string& prefix) const {
    const toml::node* n = t.get(key);
    if (!n) fail(t, sub(prefix, key), "missing required field");
    return *n;
  }
  void allowOnly(const toml::table& t, std::initializer_list<std::string_view> keys,
                 const std::string& prefix) const;
  double number(const toml::node& n, const std::string& field) const;
  int64_t integer(const toml::node& n, const std::string& field, int64_t lo, int64_t hi) const;
  std::string text(const toml::node& n, const std::string& field) const;
  const toml::table& table(const toml::node& n, const std::string& field) const;
  const toml::array& array(const toml::node& n, const std::string& field) const;
  glm::dvec3 vec3(const toml::node& n, const std::string& field) const;

  void readImage(const toml::table& t);
  CameraSpec readCamera(const toml::table& t, const std::string& field) const;
  void readLight(const toml::table& t);
  void readMeshes(const toml::array& a);
  // The file's nodes as addMeshFile makes them, the one holding its triangles deferred; nullopt
  // when the file is not streamed.
  std::optional<uint32_t> addDeferredFile(const std::filesystem::path& file,
                                          const std::optional<Rgba8>& color);
  void readGenerators(const toml::array& a);
  // The generator's node as addBuiltin makes it, deferred; nullopt when it does not stream as one
  // mesh (other generators make graphs) or is a procedural object that keeps its definition
  // (without deferProcedural).
  std::optional<Generated> addDeferredGenerator(const std::string& spec);
  void readNodes(const toml::array& a);
  glm::dmat4 readTransform(const toml::table& t, const std::string& field) const;
  void addName(const toml::table& t, const std::string& prefix, Entry entry);
  void checkCycles(const toml::array& nodes) const;

  std::filesystem::path path_;
  std::string file_;
  std::filesystem::path dir_;
  Scene scene_;
  std::map<std::string, Entry, std::less<>> names_;
  std::map<uint32_t, DeferredChunks>* deferred_;
  bool deferProcedural_;
};

void TomlSceneReader::allowOnly(const toml::table& t, std::initializer_list<std::string_view> keys,
                                const std::string& prefix) const {
  for (const auto& [key, value] : t) {
    bool known = false;
    for (std::string_view k : keys) known = known || key.str() == k;
    if (known) continue;
    std::string list;
    for (std::string_view k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
    throw InputError(file_ + ":" + std::to_string(key.source().begin.line) + ": " +
                     sub(prefix, key.str()) + ": unknown field (expected one of: " + list + ")");
  }
}

double TomlSceneReader::number(const toml::node& n, const std::string& field) const {
  if (!n.is_number()) fail(n, field, std::string("must be a number, got ") + typeName(n.type()));
  const double v = n.value<double>().value();
  if (!std::isfinite(v)) fail(n, field, "must be finite");
  return v;
}

int64_t TomlSceneReader::integer(const toml::node& n, const std::string& field, int64_t lo,
                                 int64_t hi) const {
  if (!n.is_integer()) fail(n, field, std::string("must be an integer, got ") + typeName(n.type()));
  const int64_t v = n.value<int64_t>().value();
  if (v < lo || v > hi)
    fail(n, field,
         "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
             std::to_string(v));
  return v;
}

std::string TomlSceneReader::text(const toml::node& n, const std::string& field) const {
  if (!n.is_string()) fail(n, field, std::string("must be a string, got ") + typeName(n.type()));
  const std::string v = n.value<std::string>().value();
  if (v.empty()) fail(n, field, "must not be empty");
  return v;
}

const toml::table& TomlSceneReader::table(const toml::node& n, const std::string& field) const {
  if (!n.is_table()) fail(n, field, std::string("must be a table, got ") + typeName(n.type()));
  return *n.as_table();
}

const toml::array& TomlSceneReader::array(const toml::node& n, const std::string& field) const {
  if (!n.is_array()) fail(n, field, std::string("must be an array, got ") + typeName(n.type()));
  return *n.as_array();
}

glm::dvec3 TomlSceneReader::vec3(const toml::node& n, const std::string& field) const {
  const toml::array& a = array(n, field);
  if (a.size() != 3) fail(n, field, "must have 3 numbers, got " + std::to_string(a.size()));
  return {number(a[0], item(field, 0)), number(a[1], item(field, 1)), number(a[2], item(field, 2))};
}

void TomlSceneReader::readImage(const toml::table& t) {
  allowOnly(t, {"width", "height"}, "image");
  scene_.width = int(integer(need(t, "width", "image"), "image.width", 1, kMaxImageSide));
  scene_.height = int(integer(need(t, "height", "image"), "image.height", 1, kMaxImageSide));
}

CameraSpec TomlSceneReader::readCamera(const toml::table& t, const std::string& field) const {
  allowOnly(t, {"position", "look_at", "up", "fov", "near", "far"}, field);
  CameraSpec c;
  c.position = vec3(need(t, "position", field), sub(field, "position"));
  c.lookAt = vec3(need(t, "look_at", field), sub(field, "look_at"));
  if (c.lookAt == c.position) fail(t, sub(field, "look_at"), "must differ from position");
  if (const toml::node* n = t.get("up")) {
    c.up = vec3(*n, sub(field, "up"));
    if (glm::length(glm::cross(c.up, c.lookAt - c.position)) <= 0.0)
      fail(*n, sub(field, "up"), "must be non-zero and not parallel to the viewing direction");
  }
  if (const toml::node* n = t.get("fov")) {
    c.fovyDegrees = number(*n, sub(field, "fov"));
    if (!(c.fovyDegrees > 0.0 && c.fovyDegrees < 180.0))
      fail(*n, sub(field, "fov"), "must be in (0, 180) degrees");
  }
  if (const toml::node* n = t.get("near")) {
    c.nearPlane = number(*n, sub(field, "near"));
    if (!(c.nearPlane > 0.0)) fail(*n, sub(field, "near"), "must be > 0");
  }
  if (const toml::node* n = t.get("far")) {
    c.farPlane = number(*n, sub(field, "far"));
    if (!(c.farPlane > c.nearPlane)) fail(*n, sub(field, "far"), "must be > near");
  }
  return c;
}

void TomlSceneReader::readLight(const toml::table& t) {
  allowOnly(t, {"direction", "ambient"}, "light");
  if (const toml::node* n = t.get("direction")) {
    scene_.light.direction = vec3(*n, "light.direction");
    if (!(glm::length(scene_.light.direction) > 0.0))
      fail(*n, "light.direction", "must be non-zero");
  }
  if (const toml::node* n = t.get("ambient")) {
    scene_.light.ambient = number(*n, "light.ambient");
    if (scene_.light.ambient < 0.0 || scene_.light.ambient > 1.0)
      fail(*n, "light.ambient", "must be in [0, 1]");
  }
}

void TomlSceneReader::addName(const toml::table& t, const std::string& prefix, Entry entry) {
  const toml::node& n = need(t, "name", prefix);
  const std::string name = text(n, sub(prefix, "name"));
  if (!names_.emplace(name, entry).second)
    fail(n, sub(prefix, "name"),
         "duplicate name '" + name + "' (meshes, generators and nodes share one namespace)");
}

void TomlSceneReader::readMeshes(const toml::array& a) {
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string field = item("meshes", i);
    const toml::table& t = table(a[i], field);
    allowOnly(t, {"name", "file", "color"}, field);
    const toml::node& fileNode = need(t, "file", field);
    std::filesystem::path file(text(fileNode, sub(field, "file")));
    if (file.is_relative()) file = dir_ / file;
    std::optional<Rgba8> color;
    if (const toml::node* n = t.get("color")) {
      const glm::dvec3 c = vec3(*n, sub(field, "color"));
      if (glm::any(glm::lessThan(c, glm::dvec3(0.0))) ||
          glm::any(glm::greaterThan(c, glm::dvec3(1.0))))
        fail(*n, sub(field, "color"), "components must be in [0, 1]");
      color = packRgb(glm::vec3(c));
    }
    uint32_t node = 0;
    try {
      const std::optional<uint32_t> deferred = addDeferredFile(file, color);
      node = deferred ? *deferred : addMeshFile(scene_, file, color);
    } catch (const InputError& e) {
      fail(fileNode, sub(field, "file"), e.what());
    }
    addName(t, field, {Kind::kMesh, node, i, std::nullopt});
  }
}

std::optional<uint32_t> TomlSceneReader::addDeferredFile(const std::filesystem::path& file,
                                                         const std::optional<Rgba8>& color) {
  if (!deferred_ || !MeshStream::streams(file)) return std::nullopt;
  std::string why;
  std::shared_ptr<const MeshStream> stream = MeshStream::open(file, why);
  if (!stream) return std::nullopt;
  const auto [node, holder] = stream->addNodes(scene_);
  scene_.nodes[holder].deferred = DeferredMesh{stream->triangles(), stream->storedBounds()};
  scene_.stats.merge(stream->stats());
  deferred_->emplace(holder, [stream, color](const std::function<void(const Mesh&)>& to) {
    if (!color) return stream->forEachChunk(to);
    stream->forEachChunk([&](const Mesh& chunk) {
      Mesh coloured = chunk;
      coloured.colors.assign(1, *color);
      to(coloured);
    });
  });
  return node;
}

std::optional<Generated> TomlSceneReader::addDeferredGenerator(const std::string& spec) {
  if (!deferred_) return std::nullopt;
  std::optional<BuiltinChunks> chunks = builtinChunks(spec);
  if (!chunks || (chunks->procedural && !deferProcedural_)) return std::nullopt;
  // One pass for the count and box, as opening a mesh file reads it once.
  DeferredMesh mesh;
  scene_.stats.merge(chunks->generate([&](const Mesh& chunk) {
    mesh.triangles += chunk.size();
    for (const glm::vec3& p : chunk.positions) mesh.bounds.extend(glm::dvec3(p));
  }));
  Generated g;
  g.root = scene_.addNode(chunks->name);
  g.camera = chunks->camera;
  scene_.nodes[g.root].deferred = mesh;
  deferred_->emplace(g.root, [generate = std::move(chunks->generate)](
                                 const std::function<void(const Mesh&)>& to) { generate(to); });
  return g;
}

void TomlSceneReader::readGenerators(const toml::array& a) {
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string field = item("generators", i);
    const toml::table& t = table(a[i], field);
    allowOnly(t, {"name", "spec"}, field);
    const toml::node& specNode = need(t, "spec", field);
    std::string spec = text(specNode, sub(field, "spec"));
    if (spec.rfind("builtin:", 0) == 0) spec = spec.substr(8);
    Generated g;
    try {
      const std::optional<Generated> deferred = addDeferredGenerator(spec);
      g = deferred ? *deferred : addBuiltin(scene_, spec, dir_);
    } catch (const InputError& e) {
      fail(specNode, sub(field, "spec"), e.what());
    }
    addName(t, field, {Kind::kGenerator, g.root, i, g.camera});
  }
}

glm::dmat4 TomlSceneReader::readTransform(const toml::table& t, const std::string& field) const {
  if (const toml::node* n = t.get("matrix")) {
    for (std::string_view other : {"translate", "rotate", "scale"})
      if (t.get(other))
        fail(*n, sub(field, "matrix"), "cannot be combined with " + std::string(other));
    const std::string mf = sub(field, "matrix");
    const toml::array& rows = array(*n, mf);
    if (rows.size() != 4) fail(*n, mf, "must have 4 rows of 4 numbers");
    glm::dmat4 m;
    for (size_t r = 0; r < 4; ++r) {
      const toml::array& row = array(rows[r], item(mf, r));
      if (row.size() != 4) fail(rows[r], item(mf, r), "must have 4 numbers");
      for (size_t c = 0; c < 4; ++c) m[int(c)][int(r)] = number(row[c], item(item(mf, r), c));
    }
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
      fail(rows[3], item(mf, 3), "must be [0, 0, 0, 1] (affine transforms only)");
    if (!(std::abs(glm::determinant(glm::dmat3(m))) > 0.0)) fail(*n, mf, "is singular");
    return m;
  }
  glm::dmat4 m(1.0);
  if (const toml::node* n = t.get("translate"))
    m = glm::translate(m, vec3(*n, sub(field, "translate")));
  if (const toml::node* n = t.get("rotate")) {
    const std::string rf = sub(field, "rotate");
    const toml::table& r = table(*n, rf);
    allowOnly(r, {"axis", "degrees", "euler"}, rf);
    const double toRad = std::numbers::pi / 180.0;
    if (const toml::node* e = r.get("euler")) {
      if (r.get("axis") || r.get("degrees"))
        fail(*e, sub(rf, "euler"), "cannot be combined with axis/degrees");
      const glm::dvec3 a = vec3(*e, sub(rf, "euler")) * toRad;
      // X first, then Y, then Z.
      m = glm::rotate(m, a.z, glm::dvec3(0, 0, 1));
      m = glm::rotate(m, a.y, glm::dvec3(0, 1, 0));
      m = glm::rotate(m, a.x, glm::dvec3(1, 0, 0));
    } else {
      const glm::dvec3 axis = vec3(need(r, "axis", rf), sub(rf, "axis"));
      if (!(glm::length(axis) > 0.0)) fail(*r.get("axis"), sub(rf, "axis"), "must be non-zero");
      const double degrees = number(need(r, "degrees", rf), sub(rf, "degrees"));
      m = glm::rotate(m, degrees * toRad, glm::normalize(axis));
    }
  }
  if (const toml::node* n = t.get("scale")) {
    const std::string sf = sub(field, "scale");
    const glm::dvec3 s = n->is_number() ? glm::dvec3(number(*n, sf)) : vec3(*n, sf);
    if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) fail(*n, sf, "must be non-zero");
    m = glm::scale(m, s);
  }
  return m;
}

void TomlSceneReader::readNodes(const toml::array& a) {
  // Names first, so nodes may reference nodes defined later in the file.
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string field = item("nodes", i);
    const toml::table& t = table(a[i], field);
    allowOnly(t, {"name", "instances"}, field);
    const toml::node& name = need(t, "name", field);
    addName(t, field,
            {Kind::kNode, scene_.addNode(text(name, sub(field, "name"))), i, std::nullopt});
  }
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string field = item("nodes", i);
    const toml::table& t = *a[i].as_table();
    const uint32_t node = names_.find(t["name"].value<std::string>().value())->second.node;
    const std::string inf = sub(field, "instances");
    const toml::array& list = array(need(t, "instances", field), inf);
    for (size_t k = 0; k < list.size(); ++k) {
      const std::string f = item(inf, k);
      const toml::table& inst = table(list[k], f);
      allowOnly(inst, {"node", "translate", "rotate", "scale", "matrix"}, f);
      const toml::node& ref = need(inst, "node", f);
      const std::string target = text(ref, sub(f, "node"));
      const auto it = names_.find(target);
      if (it == names_.end()) fail(ref, sub(f, "node"), "unknown node '" + target + "'");
      scene_.nodes[node].instances.push_back({it->second.node, readTransform(inst, f)});
    }
  }
  checkCycles(a);
}

// "a -> b -> a": the names on `path` from `target` on, back to `target`.
template <class Path>
std::string cycleText(const toml::array& nodes, const Path& path, size_t target) {
  const auto name = [&](size_t i) { return (*nodes[i].as_table())["name"].value<std::string>().value(); };
  std::string text;
  bool on = false;
  for (const auto& p : path) {
    on = on || p.node == target;
    if (on) text += name(p.node) + " -> ";
  }
  return text + name(target);
}

void TomlSceneReader::checkCycles(const toml::array& nodes) const {
  // Meshes and generators are leaves here (generators are acyclic by construction). Iterative
  // DFS (a chain of 10^5 nodes would overflow a recursive one): `path` holds the nodes from where
  // the walk started, each with its next instance.
  enum : uint8_t { kNew, kActive, kDone };
  std::vector<uint8_t> state(nodes.size(), kNew);
  struct OnPath {
    size_t node, next;
  };
  const auto instancesOf = [&](size_t i) -> const toml::array& {
    return *(*nodes[i].as_table())["instances"].as_array();
  };
  for (size_t start = 0; start < nodes.size(); ++start) {
    if (state[start] != kNew) continue;
    std::vector<OnPath> path{{start, 0}};
    state[start] = kActive;
    while (!path.empty()) {
      OnPath& top = path.back();
      const toml::array& list = instancesOf(top.node);
      if (top.next == list.size()) {
        state[top.node] = kDone;
        path.pop_back();
        continue;
      }
      const size_t k = top.next++;
      const toml::node& ref = *list[k].as_table()->get("node");
      const Entry& e = names_.find(ref.value<std::string>().value())->second;
      if (e.kind != Kind::kNode || state[e.index] == kDone) continue;
      const std::string field = item("nodes[" + std::to_string(top.node) + "].instances", k) + ".node";
      if (state[e.index] == kActive) fail(ref, field, "instancing cycle: " + cycleText(nodes, path, e.index));
      if (path.size() > size_t(kMaxInstanceDepth))
        fail(ref, field,
             "instances nest deeper than " + std::to_string(kMaxInstanceDepth) + " levels");
      state[e.index] = kActive;
      path.push_back({e.index, 0});
    }
  }
}

Scene TomlSceneReader::read() {
  toml::table doc;
  try {
    std::ifstream in(path_, std::ios::binary);
    if (in) {
      // Checked, then parsed from the same bytes.
      const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      checkTomlText(text, file_);
      doc = toml::parse(text, path_.string());
    } else {
      doc = toml::parse_file(path_.string());  // its error says why the file cannot be read
    }
  } catch (const toml::parse_error& e) {
    throw InputError(file_ + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) +
                     ": parse error: " + std::string(e.description()));
  }
  scene_.source = file_;
  allowOnly(doc, {"root", "image", "camera", "keyframes", "light", "meshes", "generators", "nodes"},
            "");
  if (const toml::node* n = doc.get("image")) readImage(table(*n, "image"));
  if (const toml::node* n = doc.get("camera"))
    scene_.camera = readCamera(table(*n, "camera"), "camera");
  if (const toml::node* n = doc.get("keyframes")) {
    const toml::array& a = array(*n, "keyframes");
    for (size_t i = 0; i < a.size(); ++i)
      scene_.keyframes.push_back(
          readCamera(table(a[i], item("keyframes", i)), item("keyframes", i)));
  }
  if (const toml::node* n = doc.get("light")) readLight(table(*n, "light"));
  if (const toml::node* n = doc.get("meshes")) readMeshes(array(*n, "meshes"));
  if (const toml::node* n = doc.get("generators")) readGenerators(array(*n, "generators"));
  if (const toml::node* n = doc.get("nodes")) readNodes(array(*n, "nodes"));

  const toml::node& rootNode = need(doc, "root", "");
  const std::string root = text(rootNode, "root");
  const auto it = names_.find(root);
  if (it == names_.end()) fail(rootNode, "root", "unknown node '" + root + "'");
  scene_.root = it->second.node;
  // A generator used as the whole scene brings its default view unless the file sets one.
  if (!scene_.camera && it->second.camera) scene_.camera = it->second.camera;
  scene_.finalize();
  return std::move(scene_);
}

}  // namespace

Scene loadTomlScene(const std::filesystem::path& path) {
  std::error_code ec;
  require(std::filesystem::is_regular_file(path, ec), path.string(), "file not found");
  return TomlSceneReader(path, nullptr).read();
}

TomlOutline loadTomlOutline(const std::filesystem::path& path, bool deferProcedural) {
  std::error_code ec;
  require(std::filesystem::is_regular_file(path, ec), path.string(), "file not found");
  auto deferred = std::make_shared<std::map<uint32_t, DeferredChunks>>();
  TomlOutline out;
  out.scene = TomlSceneReader(path, deferred.get(), deferProcedural).read();
  out.read = [deferred](uint32_t node, const std::function<void(const Mesh&)>& to) {
    deferred->at(node)(to);
  };
  return out;
}

}  // namespace lzb
