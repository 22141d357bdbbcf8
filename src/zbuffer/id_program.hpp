#pragma once
// The shader program: positions through modelView and a reversed-Z projection; each fragment
// writes its expanded triangle ID (idBase + the triangle's index in the bound vertex buffer, i.e.
// gl_VertexID / 3, 64-bit with carry) and its view depth scaled into [0, 1] (see
// depth_mapping.hpp), unless that depth is beyond farClip. Needs a current context.
#include <cstdint>
#include <glm/glm.hpp>

namespace lzb::gl {

class IdProgram {
 public:
  IdProgram();
  ~IdProgram();
  IdProgram(const IdProgram&) = delete;
  IdProgram& operator=(const IdProgram&) = delete;

  void use() const;
  void setProjection(const glm::mat4& projection) const;
  void setDepthScale(float scale) const;
  // Fragments with view depth > depth are discarded (+inf keeps all).
  void setFarClip(float depth) const;
  void setModelView(const glm::mat4& modelView) const;
  // ID of triangle 0 of the bound vertex buffer (modulo 2^64, so it may "precede" ID 0).
  void setIdBase(uint64_t idBase) const;

 private:
  unsigned program_ = 0;
  int modelView_ = -1, projection_ = -1, idBase_ = -1, depthScale_ = -1, farClip_ = -1;
};

}  // namespace lzb::gl
