#include "src/cli/build_tree_command.hpp"

#include <cstdio>

#include "src/core/error.hpp"
#include "src/core/system.hpp"
#include "src/core/timer.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"
#include "src/scene/load.hpp"

namespace lzb {

void addBuildTreeOptions(CLI::App& c, BuildTreeArgs& a) {
  c.add_option("scene", a.scene, "mesh file, scene.toml or builtin:NAME?key=value")->required();
  c.add_option("--out,-o", a.out, "the tree store to write")->required();
  c.add_option("--c", a.c, "sample size constant: p = exp(-exp(-c)) per stopping node")
      ->capture_default_str();
  c.add_option("--seed", a.seed, "seed of the drawings")->capture_default_str();
  c.add_option("--leaf-triangles", a.leafTriangles, "octree cells with more triangles are split")
      ->capture_default_str();
  c.add_option("--threads,-t", a.threads, "threads (0: the cores this process owns)")
      ->capture_default_str();
  c.add_flag("--quiet,-q", a.quiet, "no progress lines");
}

int runBuildTree(const BuildTreeArgs& a, const mpi::Group& g) {
  require(a.threads >= 0 && a.threads <= 1024, "--threads", "must be in [0, 1024]");
  const sampletree::TreeParams params{a.c, a.seed, a.leafTriangles};
  sampletree::validateParams(params);
  const Scene scene = loadScene(a.scene, a.quiet || !g.root());
  Stopwatch clock;
  const int threads = a.threads > 0 ? a.threads : coresOwned();
  const sampletree::SampleTree tree = sampletree::buildTree(scene, params, threads);
  const double buildSeconds = clock.lap();
  if (!g.root()) return 0;
  sampletree::writeTree(tree, a.out);
  if (!a.quiet)
    std::printf("lzb: sample tree of %llu triangles in %zu nodes (%.1f s), %llu bytes written to %s\n",
                (unsigned long long)tree.triangles(), tree.nodes.size(), buildSeconds,
                (unsigned long long)sampletree::storeBytes(tree), a.out.c_str());
  return 0;
}

}  // namespace lzb
