// The sample tree end to end: `lzb build-tree` writes a store that `render --method sampletree
// --tree` reads (the same image as the tree built in memory), damaged stores are refused with
// exit status 2 naming the store and nothing written, and the accuracy against raycast on a
// scanned mesh.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/files.hpp"
#include "tests/support/meshes.hpp"

namespace lzb::test {
namespace {

namespace fs = std::filesystem;

std::string bunny() {
  return scannedMesh("bunny00.off");
}

void writeBytes(const fs::path& p, const std::vector<char>& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

const std::string kScene = "'builtin:sphereflake?depth=2'";
const std::string kView = " --width 160 --height 120 --frames 2 --quiet";

fs::path buildStore(const fs::path& dir, const std::string& scene, const std::string& extra = "") {
  const fs::path store = dir / "tree.lzbtree";
  const RunResult r = runLzb("build-tree " + scene + " --out " + store.string() + " --quiet " + extra);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(store));
  return store;
}

TEST(SampleTreeCli, StoredTreeRendersLikeTheTreeBuiltInMemory) {
  const fs::path dir = freshDir("sampletree_stored");
  // Leaves of 32 triangles: the sphereflake this small then stops at inner cells, so splats are
  // drawn too (with the default 128 every cell in view is a leaf larger than a splat).
  const fs::path store = buildStore(dir, kScene, "--seed 4 --leaf-triangles 32");
  // Splats of 3 x 3: the sphereflake at this size stops at cells of up to 9 pixels.
  const RunResult a = runLzb("render " + kScene + " --method sampletree --tree " + store.string() +
                             " --seed 99 --splat 3" + kView + " --out " + (dir / "stored").string());
  ASSERT_EQ(a.status, 0) << a.output;
  const RunResult b =
      runLzb("render " + kScene + " --method sampletree --seed 4 --splat 3" +
             " --leaf-triangles 32" + kView + " --out " + (dir / "memory").string());
  ASSERT_EQ(b.status, 0) << b.output;
  for (const char* f : {"frame_0000.exr", "frame_0001.exr", "frame_0000.png"})
    EXPECT_EQ(fileBytes(dir / "stored" / f), fileBytes(dir / "memory" / f)) << f;
  const nlohmann::json rep = readJson(dir / "stored" / "report.json");
  const nlohmann::json& frame = rep["frames"][0];
  EXPECT_GT(frame["counts"]["triangles_drawn"].get<double>(), 0.0);
  EXPECT_GT(frame["counts"]["splats_drawn"].get<double>(), 0.0);
  EXPECT_EQ(rep["setup"]["counts"]["tree_bytes"].get<double>(), double(fs::file_size(store)))
      << rep["setup"].dump();
  EXPECT_EQ(rep["setup"]["counts"]["tree_seed"].get<double>(), 4.0) << "the store's seed, not --seed";
}

// Out of core (--mem-mb, buckets of ~6,000 triangles on 2 threads): a loaded scene streamed and a
// generator streamed without loading write the in-memory build's store byte for byte, and leave
// no scratch files.
TEST(SampleTreeCli, OutOfCoreBuildWritesTheInMemoryStore) {
  for (const std::string& scene : {kScene, std::string("'builtin:landscape?objects=800'")}) {
    const fs::path dir = freshDir("sampletree_external");
    const RunResult a = runLzb("build-tree " + scene + " --threads 2 --quiet --out " +
                               (dir / "memory.lzbtree").string());
    ASSERT_EQ(a.status, 0) << a.output;
    const RunResult b = runLzb("build-tree " + scene + " --threads 2 --mem-mb 4 --out " +
                               (dir / "external.lzbtree").string());
    ASSERT_EQ(b.status, 0) << b.output;
    EXPECT_NE(b.output.find("built out of core"), std::string::npos) << b.output;
    EXPECT_EQ(b.output.find(" 1 buckets"), std::string::npos) << "one bucket: nothing split\n" << b.output;
    EXPECT_EQ(fileBytes(dir / "external.lzbtree"), fileBytes(dir / "memory.lzbtree")) << scene;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2) << scene;
  }
}

// A binary PLY file (the bunny as `lzb export` writes it) is streamed by --mem-mb, not loaded,
// and gives the store of the file loaded whole by the in-memory build; a truncated file and one
// with a vertex index out of range are refused naming the file, nothing written.
TEST(SampleTreeCli, OutOfCoreBuildStreamsAPlyFile) {
  if (bunny().empty()) GTEST_SKIP() << "no test meshes (scripts/fetch-test-meshes.sh)";
  const fs::path dir = freshDir("sampletree_ply");
  const fs::path ply = dir / "bunny.ply";
  ASSERT_EQ(runLzb("export " + bunny() + " " + ply.string() + " --quiet").status, 0);
  const RunResult a = runLzb("build-tree " + ply.string() + " --threads 2 --quiet --out " +
                             (dir / "memory.lzbtree").string());
  ASSERT_EQ(a.status, 0) << a.output;
  // 5 MiB: the budget counts the file's vertex element, which the build holds besides its buckets.
  const RunResult b = runLzb("build-tree " + ply.string() + " --threads 2 --mem-mb 5 --out " +
                             (dir / "external.lzbtree").string());
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(b.output.find("built out of core"), std::string::npos) << b.output;
  EXPECT_EQ(b.output.find("not streamed"), std::string::npos) << b.output;
  EXPECT_EQ(b.output.find(" 1 buckets"), std::string::npos) << "one bucket: nothing split\n"
                                                            << b.output;
  EXPECT_EQ(fileBytes(dir / "external.lzbtree"), fileBytes(dir / "memory.lzbtree"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);

  std::vector<char> bytes = fileBytes(ply);
  const std::string text(bytes.begin(), bytes.end());
  const size_t data = text.find("end_header\n") + 11;
  const size_t faces = std::stoul(text.substr(text.find("element vertex ") + 15)) * 12 + data;
  std::vector<char> range = bytes;
  const int32_t far = 1 << 30;
  std::memcpy(range.data() + faces + 1 + 4, &far, 4);  // face 0's second index
  bytes.resize(bytes.size() - 7);
  const fs::path bad = dir / "bad";
  fs::create_directories(bad);
  writeBytes(bad / "cut.ply", bytes);
  writeBytes(bad / "range.ply", range);
  for (const char* name : {"cut.ply", "range.ply"}) {
    const fs::path file = bad / name;
    const RunResult r = runLzb("build-tree " + file.string() + " --mem-mb 4 --quiet --out " +
                               (bad / "tree.lzbtree").string());
    EXPECT_EQ(r.status, 2) << name << ": " << r.output;
    EXPECT_NE(r.output.find(file.string() + ": " +
                            (name[0] == 'c' ? "truncated" : "malformed: face 0 uses vertex")),
              std::string::npos)
        << r.output;
    EXPECT_EQ(std::distance(fs::directory_iterator(bad), fs::directory_iterator()), 2) << name;
  }
  // The vertex element is held while the file is read: a budget below it is refused, before any
  // pass, rather than exceeded.
  const double vertexMb = double(faces - data) / 1048576.0;
  const RunResult tight =
      runLzb("build-tree " + ply.string() + " --mem-mb " + std::to_string(0.9 * vertexMb) +
             " --quiet --out " + (bad / "tree.lzbtree").string());
  EXPECT_EQ(tight.status, 2) << tight.output;
  EXPECT_NE(tight.output.find("--mem-mb: " + ply.string() + " holds"), std::string::npos)
      << tight.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(bad), fs::directory_iterator()), 2);
}

// An ASCII PLY is streamed where its lines read as the loader reads them, else loaded whole with a
// note; either way it gives the in-memory store.
TEST(SampleTreeCli, OutOfCoreBuildReadsAnAsciiPly) {
  const fs::path dir = freshDir("sampletree_ply_ascii");
  for (const std::string gap : {"", "\n"}) {
    const fs::path ply = dir / "quad.ply";
    std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 1\n"
                          "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                       << gap << "1 1 0\n0 1 0\n4 0 1 2 3\n";
    const RunResult a = runLzb("build-tree " + ply.string() + " --quiet --out " +
                               (dir / "memory.lzbtree").string());
    ASSERT_EQ(a.status, 0) << a.output;
    const RunResult b = runLzb("build-tree " + ply.string() + " --mem-mb 4 --out " +
                               (dir / "external.lzbtree").string());
    ASSERT_EQ(b.status, 0) << b.output;
    EXPECT_EQ(b.output.find("not streamed (an ASCII PLY with a blank line") != std::string::npos,
              !gap.empty())
        << b.output;
    EXPECT_EQ(fileBytes(dir / "external.lzbtree"), fileBytes(dir / "memory.lzbtree"));
  }
}

// Damage of every kind: exit status 2, the store named, no output folder.
TEST(SampleTreeCli, DamagedStoresAreRefused) {
  const fs::path dir = freshDir("sampletree_damaged");
  const fs::path store = buildStore(dir, kScene);
  const std::vector<char> good = fileBytes(store);
  struct Damage {
    std::string name, mention;
    std::vector<char> bytes;
  };
  std::vector<Damage> cases;
  cases.push_back({"truncated", "truncated", std::vector<char>(good.begin(), good.end() - 7)});
  cases.push_back({"corrupted", "corrupted", good});
  cases.back().bytes[good.size() / 2] ^= 0x20;
  cases.push_back({"version", "version", good});
  cases.back().bytes[8] = 9;
  for (const Damage& d : cases) {
    const fs::path bad = dir / (d.name + ".lzbtree"), out = dir / ("out_" + d.name);
    writeBytes(bad, d.bytes);
    const RunResult r = runLzb("render " + kScene + " --method sampletree --tree " + bad.string() +
                               kView + " --out " + out.string());
    EXPECT_EQ(r.status, 2) << d.name << ": " << r.output;
    EXPECT_NE(r.output.find(bad.string()), std::string::npos) << d.name << ": " << r.output;
    EXPECT_NE(r.output.find(d.mention), std::string::npos) << d.name << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << d.name;
  }
  // A sound store of another scene.
  const fs::path out = dir / "out_other";
  const RunResult r = runLzb("render 'builtin:sphereflake?depth=1' --method sampletree --tree " +
                             store.string() + kView + " --out " + out.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(store.string()), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Out of core (--cache-mb > 0): the same files as the store read whole, with a big cache and with
// one that holds only the largest node (the frames stream through it).
TEST(SampleTreeCli, OutOfCoreRendersLikeTheStoreReadWhole) {
  const fs::path dir = freshDir("sampletree_ooc");
  const fs::path store = buildStore(dir, kScene, "--leaf-triangles 8");
  const std::string render = "render " + kScene + " --method sampletree --tree " + store.string() +
                             " --splat 2" + kView + " --out ";
  const RunResult whole = runLzb(render + (dir / "whole").string());
  ASSERT_EQ(whole.status, 0) << whole.output;
  const RunResult big = runLzb(render + (dir / "big").string() + " --cache-mb 64 --cache-levels 2");
  ASSERT_EQ(big.status, 0) << big.output;
  const nlohmann::json rep = readJson(dir / "big" / "report.json");
  const double largest = rep["setup"]["counts"]["largest_node_bytes"].get<double>();
  char mb[64];
  std::snprintf(mb, sizeof(mb), "%.17g", (largest + 1.0) / (1024.0 * 1024.0));
  const RunResult tiny = runLzb(render + (dir / "tiny").string() + " --cache-mb " + mb);
  ASSERT_EQ(tiny.status, 0) << tiny.output;
  for (const char* run : {"big", "tiny"})
    for (const char* f : {"frame_0000.exr", "frame_0001.exr", "frame_0000.png", "frame_0001.png"})
      EXPECT_EQ(fileBytes(dir / run / f), fileBytes(dir / "whole" / f)) << run << " " << f;
  const nlohmann::json& frame = rep["frames"][0]["counts"];
  EXPECT_GT(frame["nodes_loaded"].get<double>(), 0.0) << frame.dump();
  // Frame 0 loads every node it draws (48 bytes a triangle), and what its prefetch loaded so far.
  const double bytes = frame["bytes_read"].get<double>();
  EXPECT_GE(bytes, 48.0 * frame["triangles_drawn"].get<double>()) << frame.dump();
  EXPECT_EQ(std::fmod(bytes, 48.0), 0.0) << frame.dump();
  const nlohmann::json tinyRep = readJson(dir / "tiny" / "report.json");
  EXPECT_GT(tinyRep["frames"][0]["counts"]["draw_batches"].get<double>(), 1.0);
  // Below the largest node: refused before rendering.
  std::snprintf(mb, sizeof(mb), "%.17g", (largest / 2) / (1024.0 * 1024.0));
  const RunResult refused = runLzb(render + (dir / "refused").string() + " --cache-mb " + mb);
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("--cache-mb"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir / "refused"));
  // A node cache for a tree built in memory is refused too.
  const RunResult inMemory = runLzb("render " + kScene + " --method sampletree --cache-mb 8" + kView +
                                    " --out " + (dir / "memory").string());
  EXPECT_EQ(inMemory.status, 2) << inMemory.output;
  EXPECT_NE(inMemory.output.find("--tree"), std::string::npos) << inMemory.output;
}

// A store keeps the outline of its scene and the tree shades from its own triangles, so a render
// from a store (here built out of core from a generator that was never loaded) does not load the
// scene: the same frames as a run that loads it (for the raycast reference) and as the store read
// whole, the same scene in the report.
TEST(SampleTreeCli, StoreRendersWithoutLoadingTheScene) {
  const std::string scene = "'builtin:landscape?objects=800'";
  const fs::path dir = freshDir("sampletree_outline");
  const fs::path store = dir / "tree.lzbtree";
  const RunResult built = runLzb("build-tree " + scene + " --threads 2 --mem-mb 4 --quiet --out " +
                                 store.string());
  ASSERT_EQ(built.status, 0) << built.output;
  const std::string render = " --method sampletree --tree " + store.string() + kView + " --out ";
  const RunResult unread = runLzb("render " + scene + render + (dir / "unread").string() + " --cache-mb 1");
  ASSERT_EQ(unread.status, 0) << unread.output;
  const RunResult loaded = runLzb("render " + scene + render + (dir / "loaded").string() +
                                  " --cache-mb 1 --reference raycast");
  ASSERT_EQ(loaded.status, 0) << loaded.output;
  const RunResult whole = runLzb("render " + scene + render + (dir / "whole").string());
  ASSERT_EQ(whole.status, 0) << whole.output;
  for (const char* run : {"loaded", "whole"})
    for (const char* f : {"frame_0000.exr", "frame_0001.exr", "frame_0000.png", "frame_0001.png"})
      EXPECT_EQ(fileBytes(dir / run / f), fileBytes(dir / "unread" / f)) << run << " " << f;
  nlohmann::json a = readJson(dir / "unread" / "report.json")["scene"];
  nlohmann::json b = readJson(dir / "loaded" / "report.json")["scene"];
  EXPECT_FALSE(a["loaded"].get<bool>());
  EXPECT_TRUE(b["loaded"].get<bool>());
  a.erase("loaded");
  b.erase("loaded");
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["source"], "builtin:landscape?objects=800");
}

// A block of triangles corrupted in a store that opens soundly (header, block table, node table):
// out of core the frame that reads it fails with exit status 2 naming the store, on 1 and on 2
// ranks (every rank ends, no hang).
TEST(SampleTreeCli, OutOfCoreCorruptionFoundAtRenderTimeEndsTheJob) {
  const fs::path dir = freshDir("sampletree_ooc_corrupt");
  const fs::path store = buildStore(dir, kScene, "--leaf-triangles 8");
  std::vector<char> bytes = fileBytes(store);
  // Every byte of the triangle positions and IDs after the node table's blocks: whatever a frame
  // draws is damaged, while the store still opens.
  uint64_t nodes = 0;
  std::memcpy(&nodes, bytes.data() + 16, 8);
  uint64_t payload = 0;
  std::memcpy(&payload, bytes.data() + 96, 8);
  const uint64_t from = (nodes * 72 / 65536 + 1) * 65536;
  const uint64_t to = payload - (payload - nodes * 72) / 48 * 4;  // before the colours
  ASSERT_LT(from, to) << "the scene must span more blocks than the node table";
  for (uint64_t at = from; at < to; at += 997) bytes[size_t(128 + at)] ^= 0x08;
  writeBytes(store, bytes);
  const std::string args = "render " + kScene + " --method sampletree --tree " + store.string() +
                           " --cache-mb 64 --threads 1" + kView + " --out ";
  const RunResult one = runLzb(args + (dir / "one").string());
  EXPECT_EQ(one.status, 2) << one.output;
  EXPECT_NE(one.output.find(store.string()), std::string::npos) << one.output;
  EXPECT_NE(one.output.find("corrupted"), std::string::npos) << one.output;
  const RunResult two = runLzb(args + (dir / "two").string(),
                               mpiexecPrefix(2, 120));
  EXPECT_EQ(two.status, 2) << two.output;
  EXPECT_NE(two.output.find("corrupted"), std::string::npos) << two.output;
  // The node server meets the damage: it ends the job, naming the store; the render rank, waiting
  // for the reply, does not hang.
  const RunResult served = runLzb(args + (dir / "served").string() + " --node-server",
                                  mpiexecPrefix(2, 120));
  EXPECT_EQ(served.status, 2) << served.output;
  EXPECT_NE(served.output.find(store.string()), std::string::npos) << served.output;
  EXPECT_NE(served.output.find("corrupted"), std::string::npos) << served.output;
}

// --node-server needs a store, a node cache, at least 2 ranks and one frame group: otherwise exit
// status 2 naming --node-server, nothing written. A store the server cannot open fails every rank
// alike (one message naming the store); so do the refusals after it has started serving.
TEST(SampleTreeCli, NodeServerRefusals) {
  const fs::path dir = freshDir("sampletree_node_server_refused");
  const fs::path store = buildStore(dir, kScene, "--leaf-triangles 8");
  const std::string two = mpiexecPrefix(2, 120);
  const std::string render = "render " + kScene + " --method sampletree --node-server" + kView;
  const std::string tree = " --tree " + store.string();
  struct Case {
    std::string name, args, prefix, mention;
  };
  const std::vector<Case> cases = {
      {"no_tree", render + " --cache-mb 8", two, "--tree"},
      {"no_cache", render + tree, two, "--cache-mb"},
      {"one_rank", render + tree + " --cache-mb 8", "", "2 MPI ranks"},
      {"frame_groups", render + tree + " --cache-mb 8 --frame-groups 2", two, "--frame-groups"},
  };
  for (const Case& c : cases) {
    const fs::path out = dir / ("out_" + c.name);
    const RunResult r = runLzb(c.args + " --out " + out.string(), c.prefix);
    EXPECT_EQ(r.status, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("--node-server"), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.mention), std::string::npos) << c.name << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  std::vector<char> bytes = fileBytes(store);
  bytes.resize(bytes.size() - 7);
  const fs::path bad = dir / "truncated.lzbtree", out = dir / "out_truncated";
  writeBytes(bad, bytes);
  const RunResult r = runLzb(render + " --cache-mb 8 --tree " + bad.string() + " --out " + out.string(), two);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(bad.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("rank "), std::string::npos) << "one message for every rank: " << r.output;
  EXPECT_FALSE(fs::exists(out));
  // A refusal after the server started serving (a cache below the largest node, on 3 ranks): every
  // render rank says goodbye, the server stops, no rank hangs; a store of another scene is refused
  // on every rank before.
  const std::string three = mpiexecPrefix(3, 120);
  const RunResult small = runLzb(render + tree + " --cache-mb 0.0001 --out " + (dir / "small").string(), three);
  EXPECT_EQ(small.status, 2) << small.output;
  EXPECT_NE(small.output.find("--cache-mb"), std::string::npos) << small.output;
  EXPECT_FALSE(fs::exists(dir / "small"));
  const RunResult other = runLzb("render 'builtin:sphereflake?depth=1' --method sampletree --node-server "
                                 "--cache-mb 8" + tree + kView + " --out " + (dir / "other").string(), two);
  EXPECT_EQ(other.status, 2) << other.output;
  EXPECT_NE(other.output.find(store.string()), std::string::npos) << other.output;
  EXPECT_FALSE(fs::exists(dir / "other"));
}

TEST(SampleTreeCli, BuildTreeRefusesBadInputAndWritesNothing) {
  const fs::path dir = freshDir("sampletree_build_bad");
  const fs::path store = dir / "tree.lzbtree";
  // The last: 2^25 expanded triangles, above the in-core limit of this milestone.
  for (const std::string& args : {std::string("build-tree builtin:teapot"), "build-tree " + kScene + " --c -1",
                                  "build-tree " + kScene + " --leaf-triangles 0",
                                  "build-tree " + kScene + " --mem-mb 0.001",
                                  "build-tree " + kScene + " --mem-mb -5",
                                  std::string("build-tree 'builtin:landscape?objects=-1' --mem-mb 64"),
                                  std::string("build-tree 'builtin:chessboard?n=4096'")}) {
    const RunResult r = runLzb(args + " --out " + store.string() + " --quiet");
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(fs::exists(store)) << args;
    EXPECT_TRUE(fs::is_empty(dir)) << args;
  }
  // Out of core into a folder that does not exist: refused, the folder not made.
  const RunResult missing = runLzb("build-tree " + kScene + " --mem-mb 16 --quiet --out " +
                                   (dir / "no" / "tree.lzbtree").string());
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("--out"), std::string::npos) << missing.output;
  EXPECT_TRUE(fs::is_empty(dir));
  // Rendering such a scene without a store refuses it too, before any output.
  const RunResult r = runLzb("render 'builtin:chessboard?n=4096' --method sampletree --quiet --out " +
                             (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("in memory"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Where a frame may be wrong: only around the nodes where the traversal stopped (every other
// visited node draws all its triangles with the exact native z-buffer, and a stopped node's
// subtree lies in its cell's bounding sphere, its splat on the splat^2 pixels around its
// representative). The renderer reports the union of those pixels as approximated_pixels; a
// frame's wrong covered pixels, judged against raycast, can be no more, besides those the exact
// z-buffer itself gets wrong on the frame (a near tie of depths that float ray casting resolves
// otherwise: 1 pixel of 10^4 in the sub-pixel field). Checked on a scanned mesh large on screen
// (few stops), the same mesh small (most cells stop) for splat sizes 1-5, and a sub-pixel field
// of scanned meshes.
void expectWithinApproximated(const std::string& scene, const std::string& view,
                              const std::string& treeArgs, const std::string& name,
                              double minRate) {
  const fs::path dir = freshDir(name);
  const std::string frames = " --reference raycast --frames 2 --quiet " + view + " --out ";
  const RunResult r = runLzb("render '" + scene + "' --method sampletree " + treeArgs + frames +
                             (dir / "tree").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const RunResult z =
      runLzb("render '" + scene + "' --method zbuffer" + frames + (dir / "z").string());
  ASSERT_EQ(z.status, 0) << z.output;
  const nlohmann::json rep = readJson(dir / "tree" / "report.json");
  const nlohmann::json exact = readJson(dir / "z" / "report.json");
  for (size_t k = 0; k < rep["frames"].size(); ++k) {
    const nlohmann::json& acc = rep["frames"][k]["accuracy"];
    const double wrong = acc["covered_pixels"].get<double>() - acc["correct_covered_pixels"].get<double>();
    const double approximated = rep["frames"][k]["counts"]["approximated_pixels"].get<double>();
    const double zbufferWrong = exact["frames"][k]["accuracy"]["wrong_pixels"].get<double>();
    EXPECT_LE(wrong, approximated + zbufferWrong) << name << " " << treeArgs << ": " << acc.dump();
    EXPECT_GE(acc["correct_rate_covered"].get<double>(), minRate) << name << " " << treeArgs;
  }
}

TEST(SampleTreeCli, AccuracyAgainstRaycastOnAScannedMesh) {
  const std::string mesh = bunny();
  if (mesh.empty()) GTEST_SKIP() << "no bunny00.off (scripts/fetch-test-meshes.sh build/data)";
  // Large on screen: few cells reach a pixel, so nearly every pixel is exact.
  expectWithinApproximated(mesh, "--width 320 --height 240", "", "sampletree_bunny_large", 0.99);
  for (int splat = 1; splat <= 5; ++splat)
    expectWithinApproximated(mesh, "--width 96 --height 72", "--splat " + std::to_string(splat),
                             "sampletree_bunny_small_" + std::to_string(splat), 0.0);
  expectWithinApproximated(mesh, "--width 96 --height 72", "--stop-draw triangles",
                           "sampletree_bunny_small_triangles", 0.0);
}

TEST(SampleTreeCli, AccuracyAgainstRaycastOnASubpixelScene) {
  const fs::path armadillo = dataDir() / "armadillo.off";
  if (!fs::exists(armadillo)) GTEST_SKIP() << "no armadillo.off (scripts/fetch-test-meshes.sh build/data)";
  const std::string field = "builtin:replicated?mesh=" + armadillo.string() + "&k=4&levels=1";
  expectWithinApproximated(field, "--width 160 --height 120", "", "sampletree_field", 0.0);
  expectWithinApproximated(field, "--width 160 --height 120", "--stop-draw triangles",
                           "sampletree_field_triangles", 0.0);
}

}  // namespace
}  // namespace lzb::test
