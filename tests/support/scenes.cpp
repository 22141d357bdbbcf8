#include "tests/support/scenes.hpp"

namespace lzb::test {

Rgba8 grey(uint8_t v) {
  return packRgba8(v, v, v, 255);
}

void addQuad(Mesh& mesh) {
  mesh.add({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, grey(200));
  mesh.add({-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, grey(100));
}

Scene quadScene() {
  Scene s;
  s.source = "quad";
  s.addNode("quad");
  addQuad(s.nodes[0].mesh);
  s.finalize();
  return s;
}

void addRandomTriangles(Mesh& mesh, size_t count, double size, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (mesh.size() < count) {
    const glm::dvec3 c(u(rng), u(rng), u(rng));
    auto corner = [&] { return glm::vec3(c + size * glm::dvec3(u(rng), u(rng), u(rng))); };
    mesh.add(corner(), corner(), corner(), packRgba8(uint8_t(rng()), uint8_t(rng()), 128, 255));
  }
}

glm::dmat4 randomTransform(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(lo, hi), a(0.0, 6.283185307179586);
  glm::dvec3 axis(u(rng), u(rng), u(rng));
  if (glm::length(axis) < 1e-3) axis = {0, 0, 1};
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(u(rng), u(rng), u(rng)));
  m = glm::rotate(m, a(rng), glm::normalize(axis));
  return glm::scale(m, glm::dvec3(s(rng), s(rng), s(rng)));
}

Scene soupScene(size_t triangles, double size, uint64_t seed) {
  std::mt19937_64 rng(seed);
  Scene s;
  s.source = "soup";
  s.addNode("soup");
  addRandomTriangles(s.nodes[0].mesh, triangles, size, rng);
  s.finalize();
  return s;
}

Scene nestedScene(uint64_t seed) {
  std::mt19937_64 rng(seed);
  Scene s;
  s.source = "nested";
  const uint32_t root = s.addNode("root"), b = s.addNode("B"), a = s.addNode("A"),
                 leaf = s.addNode("leaf");
  s.root = root;
  addRandomTriangles(s.nodes[leaf].mesh, 200, 0.6, rng);
  addRandomTriangles(s.nodes[a].mesh, 20, 0.5, rng);
  for (int i = 0; i < 3; ++i)
    s.nodes[a].instances.push_back({leaf, randomTransform(rng, 0.5, 0.9)});
  addRandomTriangles(s.nodes[b].mesh, 10, 0.3, rng);
  for (int i = 0; i < 2; ++i) s.nodes[b].instances.push_back({a, randomTransform(rng, 0.6, 0.9)});
  s.nodes[b].instances.push_back({leaf, randomTransform(rng, 0.3, 0.5)});
  addRandomTriangles(s.nodes[root].mesh, 10, 0.3, rng);
  for (int i = 0; i < 2; ++i)
    s.nodes[root].instances.push_back({b, randomTransform(rng, 0.7, 1.0)});
  s.nodes[root].instances.push_back({a, randomTransform(rng, 0.6, 0.9)});
  s.nodes[root].instances.push_back({leaf, randomTransform(rng, 0.3, 0.5)});
  s.finalize();
  return s;
}

Scene translated(const Scene& inner, const glm::dvec3& t) {
  Scene s = inner;
  const uint32_t world = s.addNode("world");
  s.nodes[world].instances.push_back({inner.root, glm::translate(glm::dmat4(1.0), t)});
  s.root = world;
  s.finalize();
  return s;
}

}  // namespace lzb::test
