#include "src/core/scene_outline.hpp"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "src/core/error.hpp"

namespace lzb {

namespace {

using nlohmann::json;

json vec(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }
glm::dvec3 vecOf(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

json cameraJson(const CameraSpec& c) {
  return {{"position", vec(c.position)}, {"look_at", vec(c.lookAt)}, {"up", vec(c.up)},
          {"fovy_degrees", c.fovyDegrees}, {"near", c.nearPlane}, {"far", c.farPlane}};
}

CameraSpec cameraOf(const json& j) {
  CameraSpec c;
  c.position = vecOf(j.at("position"));
  c.lookAt = vecOf(j.at("look_at"));
  c.up = vecOf(j.at("up"));
  c.fovyDegrees = j.at("fovy_degrees").get<double>();
  c.nearPlane = j.at("near").get<double>();
  c.farPlane = j.at("far").get<double>();
  return c;
}

SceneOutline outlineOfJson(const json& j) {
  SceneOutline o;
  o.source = j.at("source").get<std::string>();
  o.bounds.lo = vecOf(j.at("bounds").at(0));
  o.bounds.hi = vecOf(j.at("bounds").at(1));
  o.uniqueTriangles = j.at("unique_triangles").get<uint64_t>();
  o.expandedTriangles = j.at("expanded_triangles").get<uint64_t>();
  o.nodes = j.at("nodes").get<uint64_t>();
  o.instanceDepth = j.at("instance_depth").get<int>();
  o.stats.loaded = j.at("loaded").get<uint64_t>();
  o.stats.degenerate = j.at("dropped_degenerate").get<uint64_t>();
  o.stats.nonFinite = j.at("dropped_nonfinite").get<uint64_t>();
  o.light.direction = vecOf(j.at("light_direction"));
  o.light.ambient = j.at("ambient").get<double>();
  if (j.contains("camera")) o.camera = cameraOf(j.at("camera"));
  for (const json& k : j.at("keyframes")) o.keyframes.push_back(cameraOf(k));
  if (j.contains("width")) o.width = j.at("width").get<int>();
  if (j.contains("height")) o.height = j.at("height").get<int>();
  return o;
}

}  // namespace

SceneOutline outlineOf(const Scene& scene) {
  SceneOutline o;
  o.source = scene.source;
  o.bounds = scene.bounds();
  o.uniqueTriangles = scene.uniqueTriangles();
  o.expandedTriangles = scene.expandedTriangles();
  o.nodes = scene.nodes.size();
  o.instanceDepth = scene.instanceDepth;
  o.stats = scene.stats;
  o.light = scene.light;
  o.camera = scene.camera;
  o.keyframes = scene.keyframes;
  o.width = scene.width;
  o.height = scene.height;
  return o;
}

std::string outlineText(const SceneOutline& o) {
  json j = {{"source", o.source},
            {"bounds", {vec(o.bounds.lo), vec(o.bounds.hi)}},
            {"unique_triangles", o.uniqueTriangles},
            {"expanded_triangles", o.expandedTriangles},
            {"nodes", o.nodes},
            {"instance_depth", o.instanceDepth},
            {"loaded", o.stats.loaded},
            {"dropped_degenerate", o.stats.degenerate},
            {"dropped_nonfinite", o.stats.nonFinite},
            {"light_direction", vec(o.light.direction)},
            {"ambient", o.light.ambient},
            {"keyframes", json::array()}};
  if (o.camera) j["camera"] = cameraJson(*o.camera);
  for (const CameraSpec& k : o.keyframes) j["keyframes"].push_back(cameraJson(k));
  if (o.width) j["width"] = *o.width;
  if (o.height) j["height"] = *o.height;
  return j.dump();
}

SceneOutline parseOutline(const std::string& text, const std::string& where) {
  try {
    return outlineOfJson(json::parse(text));
  } catch (const json::exception& e) {
    throw InputError(where + ": the scene outline is not readable: " + e.what());
  }
}

bool namesSameScene(const std::string& a, const std::string& b) {
  if (a == b) return true;
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec) && !ec;
}

SceneOutline placedMeshOutline(SceneOutline base, const Bounds& nodeBounds,
                               const glm::dmat4& placement, uint64_t triangles,
                               const LoadStats& stats) {
  const bool recentred = placement != glm::dmat4(1.0);
  base.bounds = recentred ? nodeBounds.transformed(placement) : nodeBounds;
  base.uniqueTriangles = base.expandedTriangles = triangles;
  base.nodes = recentred ? 2 : 1;
  base.instanceDepth = recentred ? 1 : 0;
  base.stats = stats;
  return base;
}

Scene sceneFromOutline(const SceneOutline& o) {
  Scene s;
  s.source = o.source;
  s.light = o.light;
  s.camera = o.camera;
  s.keyframes = o.keyframes;
  s.width = o.width;
  s.height = o.height;
  s.stats = o.stats;
  s.root = s.addNode("outline");
  s.finalize();
  s.expandedCount[s.root] = o.expandedTriangles;
  s.nodeBounds[s.root] = o.bounds;
  return s;
}

}  // namespace lzb
