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

// A procedural built-in's definition and camera, from its parameters.
struct ProceduralBuiltin {
  std::string name;
  ProceduralSpec spec;
  CameraSpec camera;
};

ProceduralBuiltin displacedBuiltin(BuiltinParams& params) {
  const std::string shape = params.text("shape", "plane");
  require(shape == "plane" || shape == "sphere", params.where("shape"),
          "must be plane or sphere, got '" + shape + "'");
  ProceduralBuiltin b{"displaced/" + shape, {}, {}};
  ProceduralSpec& spec = b.spec;
  const bool sphere = shape == "sphere";
  spec.kind = sphere ? ProceduralKind::kSphere : ProceduralKind::kPlane;
  spec.size = params.number("size", sphere ? 2.0 : 10.0, 1e-6, 1e9);
  const double amp = params.number("amp", sphere ? 0.15 * spec.size : 0.06 * spec.size, 0.0,
                                   sphere ? 0.5 * spec.size : 1e9);
  readNoise(params, spec, amp, sphere ? 1.5 / spec.size : 4.0 / spec.size, 512);
  params.finish();
  const double s = spec.size;
  b.camera.position =
      sphere ? glm::dvec3(0.0, 0.5 * s, 3.2 * s) : glm::dvec3(0.0, 0.55 * s, 0.75 * s);
  b.camera.lookAt = sphere ? glm::dvec3(0.0) : glm::dvec3(0.0, 0.0, -0.1 * s);
  b.camera.nearPlane = 0.02 * s;
  return b;
}

ProceduralBuiltin terrainBuiltin(BuiltinParams& params) {
  ProceduralBuiltin b{"terrain", {}, {}};
  ProceduralSpec& spec = b.spec;
  spec.kind = ProceduralKind::kTerrain;
  spec.size = params.number("extent", 2000.0, 1e-3, 1e9);
  const double height = params.number("height", 0.06 * spec.size, 0.0, 1e9);
  spec.octaves = 6;
  readNoise(params, spec, height, 5.0 / spec.size, 768);
  params.finish();
  // Low over the near edge, looking along the ground to the horizon: the far hills hide behind
  // the near ones (what the horizon culling of section 3.4 exploits).
  const double e = spec.size;
  const glm::dvec3 foot = spec.position(0.5, 0.95);
  b.camera.position = foot + glm::dvec3(0.0, 0.01 * e, 0.0);
  b.camera.lookAt = glm::dvec3(0.0, foot.y, -0.5 * e);
  b.camera.fovyDegrees = 50.0;
  b.camera.nearPlane = 1e-3 * e;
  return b;
}

Generated generated(Scene& scene, const ProceduralBuiltin& b, const std::string& where) {
  Generated out;
  out.root = addProcedural(scene, b.name, b.spec, where);
  out.camera = b.camera;
  return out;
}

// Grid rows a streamed chunk holds: about 2^15 triangles.
size_t rowsPerChunk(const ProceduralSpec& spec) {
  return std::max<size_t>(1, (size_t(1) << 14) / size_t(spec.tess));
}

}  // namespace

Generated generateDisplaced(Scene& scene, BuiltinParams& params) {
  return generated(scene, displacedBuiltin(params), "builtin:" + params.spec());
}

Generated generateTerrain(Scene& scene, BuiltinParams& params) {
  return generated(scene, terrainBuiltin(params), "builtin:" + params.spec());
}

std::optional<BuiltinChunks> proceduralChunks(BuiltinParams& params) {
  if (params.name() != "terrain" && params.name() != "displaced") return std::nullopt;
  const ProceduralBuiltin b =
      params.name() == "terrain" ? terrainBuiltin(params) : displacedBuiltin(params);
  BuiltinChunks chunks;
  chunks.triangles = 2 * uint64_t(b.spec.tess) * uint64_t(b.spec.tess);
  chunks.camera = b.camera;
  chunks.procedural = true;
  chunks.name = b.name;
  chunks.generate = [spec = b.spec, where = "builtin:" + params.spec()](
                        const std::function<void(const Mesh&)>& chunk) {
    LoadStats stats;
    stats.loaded = tessellateInChunks(spec, where, chunk, rowsPerChunk(spec));
    return stats;
  };
  return chunks;
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
