#include "src/scene/builtin.hpp"

#include "src/core/error.hpp"
#include "src/scene/builtin_generators.hpp"

namespace lzb {

void requireIdSpace(const BuiltinParams& params, const std::string& key, uint64_t base,
                    uint64_t factor, int64_t levels) {
  constexpr uint64_t kLimit = kMaxExpandedTriangles;
  uint64_t total = base;
  for (int64_t i = 0; i < levels; ++i) {
    require(factor == 0 || total <= kLimit / factor, params.where(key),
            "too large: the expanded scene would exceed 2^62 triangles");
    total *= factor;
  }
}

std::vector<std::string> builtinNames() {
  return {"chessboard", "city", "forest", "sphereflake", "replicated", "landscape", "displaced",
          "terrain", "halton-forest"};
}

Generated addBuiltin(Scene& scene, const std::string& spec, const std::filesystem::path& baseDir) {
  BuiltinParams params(spec);
  const std::string& name = params.name();
  if (name == "chessboard") return generateChessboard(scene, params);
  if (name == "city") return generateCity(scene, params);
  if (name == "forest") return generateForest(scene, params);
  if (name == "sphereflake") return generateSphereflake(scene, params);
  if (name == "displaced") return generateDisplaced(scene, params);
  if (name == "terrain") return generateTerrain(scene, params);
  if (name == "halton-forest") return generateHaltonForest(scene, params);
  if (name == "replicated") return generateReplicated(scene, params, baseDir);
  if (name == "landscape") return generateLandscape(scene, params);
  std::string known;
  for (const std::string& n : builtinNames()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("builtin:" + spec + ": unknown generator '" + name + "' (known: " + known + ")");
}

std::optional<BuiltinChunks> builtinChunks(const std::string& spec) {
  BuiltinParams params(spec);
  if (params.name() == "landscape") return landscapeChunks(params);
  return proceduralChunks(params);
}

}  // namespace lzb
