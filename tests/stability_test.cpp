// Numerical stability of every registered method (parameterised over makeRegisteredMethods(), like
// the conformance test): ill-conditioned scenes and cameras, each with an asserted outcome.
//
// A case that renders must: exit 0 within kHangSeconds; write no NaN or Inf (depth finite and in
// [near, far] where a triangle shows, +inf exactly where none does; no null among the report's
// numbers but psnr_aa, which is null only for an exact colour match); and reach, against
// `--reference raycast`, a correct_rate_covered of at least its well-conditioned twin's (the same
// method on the same picture without the difficulty) minus kAccuracySlack. A case whose input is
// truly unusable must exit 2 naming the culprit and write nothing. An option that only other
// methods read must leave a method's frame byte for byte as it is without the option. A splat of
// 64 pixels (the largest) must render finite and leave no covered pixel empty; its accuracy is
// the splat size's own trade, not bounded here.
//
// Scenes are TOML files written per case: the 18,200-triangle sphereflake (depth 2) and extra
// meshes (OFF, in the flake's frame), placed by one instance transform (scale s, offset o) and
// seen by a camera that the same transform carries along.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "src/core/method.hpp"
#include "src/image/frame_io.hpp"
#include "tests/support/cli_runner.hpp"

namespace lzb::test {
namespace {

namespace fs = std::filesystem;

// A rendering case may lose at most this share of covered pixels against its twin.
constexpr double kAccuracySlack = 0.01;
// A run that takes longer has hung (the slowest case renders in seconds).
constexpr int kHangSeconds = 300;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
std::string vec(const glm::dvec3& v) {
  return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]";
}

// Triangles of an extra mesh, in the flake's frame (float positions, as OFF stores them).
struct Tri {
  glm::dvec3 a, b, c;
};
std::string offText(const std::vector<Tri>& tris) {
  std::ostringstream s;
  s << "OFF\n" << 3 * tris.size() << " " << tris.size() << " 0\n";
  s.precision(9);
  for (const Tri& t : tris)
    for (const glm::dvec3& p : {t.a, t.b, t.c}) s << p.x << " " << p.y << " " << p.z << "\n";
  for (size_t i = 0; i < tris.size(); ++i)
    s << "3 " << 3 * i << " " << 3 * i + 1 << " " << 3 * i + 2 << "\n";
  return s.str();
}
void addQuad(std::vector<Tri>& t, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) {
  t.push_back({a, b, c});
  t.push_back({a, c, d});
}

struct View {
  glm::dvec3 position{3.2, 2.6, 4.4}, lookAt{0.0, 0.35, 0.0}, up{0.0, 1.0, 0.0};
  double fov = 45.0, nearPlane = 1.0, farPlane = 20.0;
  glm::dvec3 forward() const { return glm::normalize(lookAt - position); }
  glm::dvec3 right() const { return glm::normalize(glm::cross(forward(), up)); }
  glm::dvec3 upAxis() const { return glm::cross(right(), forward()); }
  // The point at view depth d, x right and y up of the axis.
  glm::dvec3 at(double d, double x, double y) const {
    return position + d * forward() + x * right() + y * upAxis();
  }
};

struct SceneSpec {
  std::string generator = "sphereflake?depth=2";  // "" for none
  std::vector<Tri> extra;                         // more triangles, in the generator's frame
  // Meshes of their own, each a node (so each is stored, and Embree recentres it, on its own).
  std::vector<std::vector<Tri>> parts;
  int chain = 0;  // identity instance levels between "world" and what it places
  double scale = 1.0;
  glm::dvec3 offset{0.0};
  View view;
  int width = 160, height = 120;
};

// The scene file: root "world" places the generator and the extra mesh by one transform, and the
// camera is that transform of the view (its clip planes scaled).
std::string tomlOf(const SceneSpec& s, const fs::path& dir) {
  const double k = s.scale;
  const glm::dvec3& o = s.offset;
  const std::string matrix = "[[" + num(k) + ", 0, 0, " + num(o.x) + "], [0, " + num(k) + ", 0, " +
                             num(o.y) + "], [0, 0, " + num(k) + ", " + num(o.z) +
                             "], [0, 0, 0, 1]]";
  std::ostringstream t;
  t << "root = \"world\"\n[image]\nwidth = " << s.width << "\nheight = " << s.height << "\n";
  t << "[camera]\nposition = " << vec(o + k * s.view.position)
    << "\nlook_at = " << vec(o + k * s.view.lookAt) << "\nup = " << vec(s.view.up)
    << "\nfov = " << num(s.view.fov) << "\nnear = " << num(k * s.view.nearPlane)
    << "\nfar = " << num(k * s.view.farPlane) << "\n";
  std::string instances;
  if (!s.generator.empty()) {
    t << "[[generators]]\nname = \"flake\"\nspec = \"" << s.generator << "\"\n";
    instances += "{ node = \"flake\", matrix = " + matrix + " }";
  }
  std::vector<std::vector<Tri>> meshes = s.parts;
  if (!s.extra.empty()) meshes.push_back(s.extra);
  for (size_t m = 0; m < meshes.size(); ++m) {
    const std::string name = "extra" + std::to_string(m);
    std::ofstream(dir / (name + ".off")) << offText(meshes[m]);
    t << "[[meshes]]\nname = \"" << name << "\"\nfile = \"" << name << ".off\"\n";
    instances += std::string(instances.empty() ? "" : ", ") + "{ node = \"" + name +
                 "\", matrix = " + matrix + " }";
  }
  // world -> c1 -> ... -> c<chain> -> the generator and the mesh.
  for (int k = s.chain; k >= 1; --k) {
    t << "[[nodes]]\nname = \"c" << k << "\"\ninstances = [" << instances << "]\n";
    instances = "{ node = \"c" + std::to_string(k) + "\" }";
  }
  t << "[[nodes]]\nname = \"world\"\ninstances = [" << instances << "]\n";
  return t.str();
}

struct Outcome {
  int status = -1;
  std::string output;
  fs::path out;
  nlohmann::json report;
};

// Renders `scene` with `method` and `args` against the raycast reference into a fresh folder.
Outcome render(const std::string& name, const SceneSpec& scene, const std::string& method,
               const std::string& args, int ranks = 1) {
  const fs::path dir = freshDir("stability_" + name + "_" + method);
  std::ofstream(dir / "scene.toml") << tomlOf(scene, dir);
  Outcome o;
  o.out = dir / "out";
  const std::string prefix = ranks > 1 ? mpiexecPrefix(ranks, kHangSeconds)
                                       : "timeout " + std::to_string(kHangSeconds) + " ";
  const RunResult r =
      runLzb("render " + (dir / "scene.toml").string() + " --method " + method +
                 " --reference raycast --quiet --out " + o.out.string() + " " + args,
             prefix);
  o.status = r.status;
  o.output = r.output;
  if (r.status == 0) o.report = readJson(o.out / "report.json");
  return o;
}

// Every number is a number (nlohmann writes NaN and Inf as null).
void expectNoNullNumbers(const nlohmann::json& j, const std::string& path) {
  if (j.is_null()) {
    ADD_FAILURE() << "report field " << path << " is null (NaN or Inf)";
  } else if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it)
      if (it.key() != "psnr_aa") expectNoNullNumbers(it.value(), path + "." + it.key());
  } else if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i)
      expectNoNullNumbers(j[i], path + "[" + std::to_string(i) + "]");
  }
}

// Depth is finite and within the clip planes where a triangle shows, +inf exactly where none does.
void expectFiniteFrame(const Outcome& o) {
  const Framebuffer fb = readFrameExr(o.out / "frame_0000.exr");
  const nlohmann::json& camera = o.report["frames"][0]["camera"];
  const double nearPlane = camera["near"].get<double>(), farPlane = camera["far"].get<double>();
  size_t bad = 0, first = fb.size();
  for (size_t i = 0; i < fb.size(); ++i) {
    const float d = fb.depth[i];
    const bool ok = fb.id[i] == kNoId
                        ? (std::isinf(d) && d > 0)
                        : (std::isfinite(d) && double(d) >= float(nearPlane) * (1 - 1e-6) &&
                           double(d) <= float(farPlane) * (1 + 1e-6));
    if (!ok && bad++ == 0) first = i;
  }
  EXPECT_EQ(bad, 0u) << "pixels with a depth outside the convention; first " << first << ": depth "
                     << (first < fb.size() ? fb.depth[first] : 0.f) << ", ID "
                     << (first < fb.size() ? fb.id[first] : 0) << " (near " << nearPlane << ", far "
                     << farPlane << ")";
  // The measured parts of the report (its parameters may hold null for an option not given).
  for (const char* part : {"scene", "setup", "frames", "summary"})
    expectNoNullNumbers(o.report[part], std::string("report.") + part);
}

double coveredRate(const Outcome& o) {
  return o.report["frames"][0]["accuracy"]["correct_rate_covered"].get<double>();
}

// What a case expects of a method. kCoarse: renders finite and leaves no pixel the reference
// covers empty, but its accuracy is the parameter's own trade (a 64-pixel splat paints 64 x 64
// blocks by design), so no twin bounds it.
enum class Expect { kRenders, kRefused, kUnchanged, kCoarse };

struct Case {
  std::string name;
  std::function<SceneSpec()> scene;
  std::string args;                       // extra lzb render arguments
  std::string twin = "well_conditioned";  // its well-conditioned counterpart (twins: themselves)
  // Per method (default kRenders): kRefused names `mention`; kUnchanged compares with the twin.
  std::function<Expect(const std::string& method)> expect = [](const std::string&) {
    return Expect::kRenders;
  };
  std::string mention;
  bool deterministic = false;  // also: 1 vs 2 threads and 1 vs 2 and 3 ranks give the same IDs
  int instanceDepth = -1;      // when set: the report's scene.instance_depth
};
Case makeCase(std::string name, std::function<SceneSpec()> scene, std::string args = "") {
  Case c;
  c.name = std::move(name);
  c.scene = std::move(scene);
  c.args = std::move(args);
  return c;
}

const std::map<std::string, Case>& cases();

// The twin's accuracy for `method`, rendered once per lzb binary (cached in a file named after
// the binary's modification time, so a rebuilt lzb renders its twins again).
double twinRate(const std::string& twin, const std::string& method) {
  const auto built = fs::last_write_time(lzbBinary()).time_since_epoch().count();
  const fs::path cache =
      workDir() / ("twin_" + twin + "_" + method + "_" + std::to_string(built) + ".txt");
  if (std::ifstream in(cache); in) {
    double v = -1.0;
    if (in >> v && v >= 0.0) return v;
  }
  const Case& c = cases().at(twin);
  // A folder of this process's own: another test may render the same twin at the same time.
  const Outcome o =
      render("twin_" + twin + "_" + std::to_string(::getpid()), c.scene(), method, c.args);
  EXPECT_EQ(o.status, 0) << "twin " << twin << ": " << o.output;
  if (o.status != 0) return 1.0;
  const double rate = coveredRate(o);
  fs::remove_all(o.out.parent_path());
  const fs::path tmp = cache.string() + ".tmp" + std::to_string(::getpid());
  std::ofstream(tmp) << num(rate);
  fs::rename(tmp, cache);
  return rate;
}

std::vector<uint8_t> fileBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Stability : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(Stability, KeepsItsAssertedBehaviour) {
  const auto& [caseName, method] = GetParam();
  const Case& c = cases().at(caseName);
  const Expect expect = c.expect(method);
  const Outcome o = render(caseName, c.scene(), method, c.args);
  ASSERT_NE(o.status, 124) << "hung: no result within " << kHangSeconds << " s";
  if (expect == Expect::kRefused) {
    EXPECT_EQ(o.status, 2) << o.output;
    EXPECT_NE(o.output.find(c.mention), std::string::npos) << o.output;
    EXPECT_FALSE(fs::exists(o.out)) << "output left in " << o.out;
    return;
  }
  ASSERT_EQ(o.status, 0) << o.output;
  expectFiniteFrame(o);
  const double rate = coveredRate(o);
  RecordProperty("correct_rate_covered", num(rate));
  if (c.instanceDepth >= 0) {
    EXPECT_EQ(o.report["scene"]["instance_depth"], c.instanceDepth);
  }
  if (expect == Expect::kUnchanged) {
    const Case& twin = cases().at(c.twin);
    const Outcome t = render("unchanged_" + caseName, twin.scene(), method, twin.args);
    ASSERT_EQ(t.status, 0) << t.output;
    EXPECT_EQ(fileBytes(o.out / "frame_0000.exr"), fileBytes(t.out / "frame_0000.exr"))
        << "an option " << method << " does not read changed its frame";
    return;
  }
  if (expect == Expect::kCoarse) {
    EXPECT_EQ(o.report["frames"][0]["accuracy"]["missing_pixels"], 0)
        << o.report["frames"][0]["accuracy"].dump();
    return;
  }
  const double twin = twinRate(c.twin, method);
  RecordProperty("twin_correct_rate_covered", num(twin));
  EXPECT_GE(rate, twin - kAccuracySlack)
      << caseName << " " << method << ": correct_rate_covered " << rate << ", its twin (" << c.twin
      << ") " << twin << "; accuracy " << o.report["frames"][0]["accuracy"].dump();
  if (!c.deterministic) return;
  // The same triangle wins every pixel however the work is split.
  const Framebuffer one = readFrameExr(o.out / "frame_0000.exr");
  const Outcome threads = render(caseName + "_t2", c.scene(), method, c.args + " --threads 2");
  ASSERT_EQ(threads.status, 0) << threads.output;
  EXPECT_EQ(readFrameExr(threads.out / "frame_0000.exr").id, one.id) << "2 threads";
  for (int ranks : {2, 3}) {
    const Outcome split =
        render(caseName + "_r" + std::to_string(ranks), c.scene(), method, c.args + " --threads 1", ranks);
    ASSERT_EQ(split.status, 0) << split.output;
    EXPECT_EQ(readFrameExr(split.out / "frame_0000.exr").id, one.id) << ranks << " ranks";
  }
}

// ---- the cases ----

constexpr double kPi = 3.14159265358979323846;

SceneSpec base() {
  return SceneSpec{};
}

// Cards parallel to the image plane at view depths 1e-3, 1e-2, ..., 1e6, each filling one of ten
// vertical stripes over the left 40 % of the image: depths over nine orders of magnitude. Each
// card is a mesh of its own: the range is across objects. (In one mesh spanning 1e6, the raycast
// reference, which recentres each mesh in float, has a 0.06 grid: it misses the 1e-3 card and
// puts the one at depth 1 at 0.989.)
std::vector<std::vector<Tri>> depthCards(const View& v, int width, int height) {
  std::vector<std::vector<Tri>> cards(10);
  const double ty = std::tan(v.fov * kPi / 360.0), tx = ty * width / height;
  for (int k = 0; k < 10; ++k) {
    const double d = std::pow(10.0, k - 3);
    const double x0 = (-1.0 + 0.08 * k - 0.01) * tx * d, x1 = (-1.0 + 0.08 * (k + 1)) * tx * d;
    const double y0 = -1.1 * ty * d, y1 = 1.1 * ty * d;
    addQuad(cards[size_t(k)], v.at(d, x0, y0), v.at(d, x1, y0), v.at(d, x1, y1), v.at(d, x0, y1));
  }
  return cards;
}

// Needles (0.5 long, 1e-5 wide), slivers (0.8 long, 1e-5 high) and specks (1e-5 across), all
// far below a pixel across (about 48 pixels per unit at depth 3), in front of the flake.
std::vector<Tri> sliversAndNeedles(const View& v) {
  std::vector<Tri> t;
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * kPi * i / 40, c = std::cos(a), s = std::sin(a);
    const glm::dvec3 root = v.at(3.0, -0.6, 0.3);
    const glm::dvec3 tip = v.at(3.0, -0.6 + 0.5 * c, 0.3 + 0.5 * s);
    const glm::dvec3 side = 0.5e-5 * (-s * v.right() + c * v.upAxis());
    t.push_back({root - side, tip, root + side});
  }
  for (int i = 0; i < 40; ++i) {
    const glm::dvec3 a = v.at(3.2, 0.2, -0.6 + 0.03 * i), b = v.at(3.2, 1.0, -0.6 + 0.03 * i);
    t.push_back({a, b, 0.5 * (a + b) + 1e-5 * v.upAxis()});
  }
  for (int i = 0; i < 40; ++i) {
    const glm::dvec3 p = v.at(2.8, -0.8 + 0.04 * i, -0.5 + 0.025 * i);
    t.push_back({p, p + 1e-5 * v.right(), p + 1e-5 * v.upAxis()});
  }
  return t;
}

// Quads whose planes contain the eye of an axis-aligned camera at (0, 0.5, 7): y = 0.5 and x = 0,
// exact in float, crossing the flake (they project to the centre row and column of an odd image).
std::vector<Tri> edgeOnQuads() {
  std::vector<Tri> t;
  addQuad(t, {-1.5, 0.5, 5}, {1.5, 0.5, 5}, {1.5, 0.5, 1}, {-1.5, 0.5, 1});
  addQuad(t, {0, -1, 5}, {0, 2, 5}, {0, 2, 1}, {0, -1, 1});
  return t;
}
View edgeOnView() {
  View v;
  v.position = {0.0, 0.5, 7.0};
  v.lookAt = {0.0, 0.5, 0.0};
  v.nearPlane = 1.0;
  v.farPlane = 20.0;
  return v;
}

// Unit cubes at -4, -2, 1 and 3 on every axis and one of side 1 at the centre: bounds [-4, 4]^3,
// so the octrees split at 0, +-2, +-1, +-3, +-0.5, ... and the cube faces lie in split planes.
std::vector<Tri> axisCubes() {
  std::vector<Tri> t;
  const auto cube = [&](glm::dvec3 lo, double side) {
    const glm::dvec3 hi = lo + side;
    const glm::dvec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                             {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                             {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                         {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    for (const auto& q : f) addQuad(t, p[q[0]], p[q[1]], p[q[2]], p[q[3]]);
  };
  for (double x : {-4.0, -2.0, 1.0, 3.0})
    for (double y : {-4.0, -2.0, 1.0, 3.0})
      for (double z : {-4.0, -2.0, 1.0, 3.0}) cube({x, y, z}, 1.0);
  cube({-0.5, -0.5, -0.5}, 1.0);
  return t;
}
// On the z axis, looking down it: the centre pixel's ray (odd image) runs along the split planes
// x = 0 and y = 0 through the octree cells' corners; the centre row and column lie in them.
View axisView(glm::dvec3 shift) {
  View v;
  v.position = glm::dvec3(0.0, 0.0, 20.0) + shift;
  v.lookAt = shift;
  v.fov = 30.0;
  v.nearPlane = 1.0;
  v.farPlane = 40.0;
  return v;
}

// Three quads in front of the flake on the plane z = 2.5 (exact in float): C and D overlap (equal
// depths: the smaller ID must win), E lies 1e-5 behind both.
std::vector<Tri> coplanarQuads(bool withBehind) {
  std::vector<Tri> t;
  addQuad(t, {-1.0, -1.0, 2.5}, {0.5, -1.0, 2.5}, {0.5, 1.5, 2.5}, {-1.0, 1.5, 2.5});
  addQuad(t, {0.0, -0.5, 2.5}, {1.5, -0.5, 2.5}, {1.5, 2.0, 2.5}, {0.0, 2.0, 2.5});
  if (withBehind)
    addQuad(t, {-0.5, -1.5, 2.49999}, {1.0, -1.5, 2.49999}, {1.0, 1.0, 2.49999},
            {-0.5, 1.0, 2.49999});
  return t;
}

// A closed sphere of radius 10 around everything (the camera inside it, like a room).
std::vector<Tri> enclosingSphere() {
  std::vector<Tri> t;
  const int slices = 24, stacks = 12;
  const auto p = [](int i, int j) {
    const double th = kPi * j / stacks, ph = 2 * kPi * i / slices;
    return 10.0 *
           glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
  };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      if (j > 0) t.push_back({p(i, j), p(i + 1, j), p(i + 1, j + 1)});
      if (j + 1 < stacks) t.push_back({p(i, j), p(i + 1, j + 1), p(i, j + 1)});
    }
  return t;
}

// A close view straight down at the centre of a chessboard of `n` squares (board side 100): the
// 10^14-triangle board (n = 2^23) and its 8192-triangle twin (n = 64) seen so that both show the
// same squares (the twin's camera is 2^17 times farther, its squares 2^17 times larger).
SceneSpec chessboardView(int64_t n, double scale) {
  SceneSpec s;
  s.generator = "chessboard?n=" + std::to_string(n);
  s.view.position = glm::dvec3(1e-4, 5e-4, 0.0) * scale;
  s.view.lookAt = glm::dvec3(1e-4, 0.0, 0.0) * scale;
  s.view.up = {0.0, 0.0, -1.0};
  s.view.nearPlane = 1e-5 * scale;
  s.view.farPlane = 1e-3 * scale;
  return s;
}

Expect onlyFor(const std::string& method, std::initializer_list<const char*> readers, Expect e) {
  for (const char* r : readers)
    if (method == r) return e;
  return Expect::kUnchanged;
}

const std::map<std::string, Case>& cases() {
  static const std::map<std::string, Case> all = [] {
    std::vector<Case> list;
    list.push_back(makeCase("well_conditioned", base));
    list.push_back(makeCase("scaled_1e-6", [] {
      SceneSpec s = base();
      s.scale = 1e-6;
      return s;
    }));
    list.push_back(makeCase("scaled_1e7", [] {
      SceneSpec s = base();
      s.scale = 1e7;
      return s;
    }));
    Case offset = makeCase("offset_1e8", [] {
      SceneSpec s = base();
      s.offset = glm::dvec3(1e8);
      return s;
    });
    // The in-core sample tree keeps float world coordinates: it refuses what they cannot resolve.
    offset.expect = [](const std::string& m) {
      return m == "sampletree" ? Expect::kRefused : Expect::kRenders;
    };
    offset.mention = "too far from the origin";
    list.push_back(offset);
    list.push_back(makeCase("near_1e-6_far_1e6", [] {
      SceneSpec s = base();
      s.view.nearPlane = 1e-6;
      s.view.farPlane = 1e6;
      return s;
    }));
    list.push_back(makeCase("depth_range_1e9", [] {
      SceneSpec s = base();
      s.parts = depthCards(s.view, s.width, s.height);
      s.view.nearPlane = 5e-4;
      s.view.farPlane = 2e6;
      return s;
    }));
    list.push_back(makeCase("slivers_and_needles", [] {
      SceneSpec s = base();
      s.extra = sliversAndNeedles(s.view);
      return s;
    }));
    Case edge = makeCase("edge_on", [] {
      SceneSpec s = base();
      s.view = edgeOnView();
      s.extra = edgeOnQuads();
      s.width = 161, s.height = 121;
      return s;
    });
    edge.twin = "edge_on_twin";
    list.push_back(edge);
    list.push_back(makeCase("edge_on_twin", [] {
      SceneSpec s = base();
      s.view = edgeOnView();
      s.width = 161, s.height = 121;
      return s;
    }));
    Case axes = makeCase("octree_planes_and_corners", [] {
      SceneSpec s;
      s.generator = "";
      s.extra = axisCubes();
      s.view = axisView(glm::dvec3(0.0));
      s.width = 161, s.height = 121;
      return s;
    });
    axes.twin = "octree_off_axis";
    list.push_back(axes);
    list.push_back(makeCase("octree_off_axis", [] {
      SceneSpec s;
      s.generator = "";
      s.extra = axisCubes();
      s.view = axisView({0.37, 0.29, 0.0});
      return s;
    }));
    Case coplanar = makeCase("coplanar_1e-5", [] {
      SceneSpec s = base();
      s.extra = coplanarQuads(true);
      return s;
    });
    coplanar.deterministic = true;
    list.push_back(coplanar);
    Case board = makeCase("instanced_1e14", [] { return chessboardView(int64_t(1) << 23, 1.0); });
    board.twin = "instanced_twin";
    // The sample tree is built in memory (no out-of-core construction yet): 10^14 is refused.
    board.expect = [](const std::string& m) {
      return m == "sampletree" ? Expect::kRefused : Expect::kRenders;
    };
    board.mention = "more than the sample tree builds in memory";
    list.push_back(board);
    list.push_back(makeCase("instanced_twin", [] { return chessboardView(64, 131072.0); }));
    Case huge = makeCase("splat_64", base, "--splat 64");
    huge.expect = [](const std::string& m) {
      return onlyFor(m, {"rzb", "hybrid", "surfels", "sampletree"}, Expect::kCoarse);
    };
    list.push_back(huge);
    Case tiny = makeCase("splat_1_gauss", base, "--splat 1 --reconstruct gauss");
    tiny.expect = [](const std::string& m) { return onlyFor(m, {"rzb"}, Expect::kRenders); };
    list.push_back(tiny);
    Case epsLow = makeCase("eps_1.000001", base, "--eps 1.000001");
    epsLow.expect = [](const std::string& m) { return onlyFor(m, {"rzb"}, Expect::kRenders); };
    list.push_back(epsLow);
    Case epsHigh = makeCase("eps_1000", base, "--eps 1000");
    epsHigh.expect = [](const std::string& m) { return onlyFor(m, {"rzb"}, Expect::kRenders); };
    list.push_back(epsHigh);
    Case epsOut = makeCase("eps_1_refused", base, "--eps 1");
    epsOut.expect = [](const std::string& m) { return onlyFor(m, {"rzb"}, Expect::kRefused); };
    epsOut.mention = "--eps";
    list.push_back(epsOut);
    // The deepest nesting there may be: world, 59 identity levels and the flake's 5 (its node,
    // 3 levels, the sphere mesh at the bottom): 64 instances on the longest path.
    Case nested = makeCase("nesting_64_levels", [] {
      SceneSpec s = base();
      s.chain = 59;
      return s;
    });
    nested.instanceDepth = kMaxInstanceDepth;
    list.push_back(nested);
    list.push_back(makeCase("camera_inside_closed_mesh", [] {
      SceneSpec s = base();
      s.extra = enclosingSphere();
      s.view.farPlane = 30.0;
      return s;
    }));
    std::map<std::string, Case> byName;
    for (Case& c : list) byName.emplace(c.name, std::move(c));
    for (const char* twin : {"edge_on_twin", "octree_off_axis", "instanced_twin"})
      byName.at(twin).twin = twin;
    return byName;
  }();
  return all;
}

std::vector<std::string> registeredNames() {
  std::vector<std::string> names;
  for (const auto& m : makeRegisteredMethods()) names.push_back(m->name());
  return names;
}

std::vector<std::string> caseNames() {
  std::vector<std::string> names;
  for (const auto& [name, c] : cases()) names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Cases, Stability,
                         ::testing::Combine(::testing::ValuesIn(caseNames()),
                                            ::testing::ValuesIn(registeredNames())),
                         [](const auto& info) {
                           // Test names take letters, digits and _: 1e-6 becomes 1em6, 1.5 1p5.
                           std::string name =
                               std::get<0>(info.param) + "_" + std::get<1>(info.param);
                           for (char& ch : name) ch = ch == '-' ? 'm' : ch == '.' ? 'p' : ch;
                           return name;
                         });

}  // namespace
}  // namespace lzb::test
