// The procedural built-ins (src/core/procedural.hpp; parameters in src/scene/README.md):
//   displaced?shape=plane|sphere&size=&amp=&freq=&octaves=&seed=&tess=   a displaced plane/sphere
//   terrain?extent=&height=&freq=&octaves=&seed=&tess=                    a fractal heightfield
//   halton-forest?trees=&levels=&seed=                                    the forest's meshed trees
// Each procedural node keeps its definition and holds its tessellation as its mesh.
#include <string>

#include "src/core/error.hpp"
#include "src/scene/builtin_generators.hpp"

namespace lzb {

namespace {

uint32_t addProcedural(Scene& scene, const std::string& name, const ProceduralSpec& spec,
                       const std::string& where) {
  const uint32_t node = scene.addNode(name);
  Node& n = scene.nodes[node];
  n.procedural = tessellate(spec, n.mesh, where);
  scene.stats.loaded += n.mesh.size();
  return node;
}

// The noise parameters every procedural built-in shares.
void readNoise(BuiltinParams& params, ProceduralSpec& spec, double amplitude, double frequency,
               int tess) {
  spec.frequency = params.number("freq", frequency, 1e-6, 1e6);
  spec.octaves = int(params.integer("octaves", spec.octaves, 1, 16));
  spec.seed = params.seed("seed", 1);
  spec.tess = int(params.integer("tess", tess, 1, kMaxTess));
  spec.amplitude = amplitude;
}

}  // namespace

Generated generateDisplaced(Scene& scene, BuiltinParams& params) {
  const std::string shape = params.text("shape", "plane");
  require(shape == "plane" || shape == "sphere", params.where("shape"),
          "must be plane or sphere, got '" + shape + "'");
  ProceduralSpec spec;
  const bool sphere = shape == "sphere";
  spec.kind = sphere ? ProceduralKind::kSphere : ProceduralKind::kPlane;
  spec.size = params.number("size", sphere ? 2.0 : 10.0, 1e-6, 1e9);
  const double amp = params.number("amp", sphere ? 0.15 * spec.size : 0.06 * spec.size, 0.0,
                                   sphere ? 0.5 * spec.size : 1e9);
  readNoise(params, spec, amp, sphere ? 1.5 / spec.size : 4.0 / spec.size, 512);
  params.finish();
  Generated out;
  out.root = addProcedural(scene, "displaced/" + shape, spec, "builtin:" + params.spec());
  CameraSpec camera;
  const double s = spec.size;
  camera.position = sphere ? glm::dvec3(0.0, 0.5 * s, 3.2 * s) : glm::dvec3(0.0, 0.55 * s, 0.75 * s);
  camera.lookAt = sphere ? glm::dvec3(0.0) : glm::dvec3(0.0, 0.0, -0.1 * s);
  camera.nearPlane = 0.02 * s;
  out.camera = camera;
  return out;
}

Generated generateTerrain(Scene& scene, BuiltinParams& params) {
  ProceduralSpec spec;
  spec.kind = ProceduralKind::kTerrain;
  spec.size = params.number("extent", 2000.0, 1e-3, 1e9);
  const double height = params.number("height", 0.06 * spec.size, 0.0, 1e9);
  spec.octaves = 6;
  readNoise(params, spec, height, 5.0 / spec.size, 768);
  params.finish();
  Generated out;
  out.root = addProcedural(scene, "terrain", spec, "builtin:" + params.spec());
  // Low over the near edge, looking along the ground to the horizon: the far hills hide behind
  // the near ones (what the horizon culling of section 3.4 exploits).
  const double e = spec.size;
  const glm::dvec3 foot = spec.position(0.5, 0.95);
  CameraSpec camera;
  camera.position = foot + glm::dvec3(0.0, 0.01 * e, 0.0);
  camera.lookAt = glm::dvec3(0.0, foot.y, -0.5 * e);
  camera.fovyDegrees = 50.0;
  camera.nearPlane = 1e-3 * e;
  out.camera = camera;
  return out;
}

Generated generateHaltonForest(Scene& scene, BuiltinParams& params) {
  const int64_t trees = params.integer("trees", 64, 0, 100000);
  const int64_t levels = params.integer("levels", 1, 0, 12);
  const uint64_t seed = params.seed("seed", 1);
  params.finish();
  // The forest generator's scene (meshed trees instanced on terrain tiles), one level by default:
  // the mesh objects the paper samples with Halton sequences (section 4).
  BuiltinParams forest("forest?trees=" + std::to_string(trees) +
                       "&levels=" + std::to_string(levels) + "&seed=" + std::to_string(seed));
  return generateForest(scene, forest);
}

}  // namespace lzb
