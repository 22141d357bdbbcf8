#include "src/zbuffer/id_program.hpp"

#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <string>

#include "src/zbuffer/gl_api.hpp"

namespace lzb::gl {

namespace {

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 modelView;   // node frame -> camera frame, composed in double (camera-relative)
uniform mat4 projection;  // reversed-Z; w_clip is the view depth
// Vertices are unindexed (3 per triangle), and gl_VertexID is the vertex's index in the buffer for
// both glDrawArrays and glDrawElements, so this is the triangle's index in the bound buffer.
flat out uint triangle;
void main() {
  triangle = uint(gl_VertexID) / 3u;
  gl_Position = projection * (modelView * vec4(position, 1.0));
}
)";

constexpr const char* kFragmentShader = R"(#version 450 core
uniform uvec2 idBase;      // expanded ID of the bound buffer's triangle 0 as (low, high) words
uniform float depthScale;  // a power of two: view depth -> [0, 0.5], exactly invertible
uniform float farClip;     // fragments deeper than this are dropped (+inf: none)
flat in uint triangle;
layout(location = 0) out uvec2 id;
void main() {
  // gl_FragCoord.w = 1 / w_clip = 1 / view depth: the one conversion to the depth convention.
  float depth = 1.0 / gl_FragCoord.w;
  // Clipping per fragment leaves the triangle's rasterization (coverage, depth) untouched.
  if (depth > farClip) discard;
  uint carry;
  uint low = uaddCarry(idBase.x, triangle, carry);
  id = uvec2(low, idBase.y + carry);  // 64-bit modular addition
  gl_FragDepth = depth * depthScale;
}
)";

unsigned compile(GLenum stage, const char* source) {
  const Api& g = api();
  const GLuint shader = g.CreateShader(stage);
  g.ShaderSource(shader, 1, &source, nullptr);
  g.CompileShader(shader);
  GLint ok = 0;
  g.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    g.GetShaderInfoLog(shader, sizeof(log), nullptr, log);
    g.DeleteShader(shader);
    throw std::runtime_error(std::string("z-buffer shader does not compile: ") + log);
  }
  return shader;
}

}  // namespace

IdProgram::IdProgram() {
  const Api& g = api();
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = g.CreateProgram();
  g.AttachShader(program_, vs);
  g.AttachShader(program_, fs);
  g.LinkProgram(program_);
  g.DeleteShader(vs);
  g.DeleteShader(fs);
  GLint ok = 0;
  g.GetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    g.GetProgramInfoLog(program_, sizeof(log), nullptr, log);
    throw std::runtime_error(std::string("z-buffer shaders do not link: ") + log);
  }
  modelView_ = g.GetUniformLocation(program_, "modelView");
  projection_ = g.GetUniformLocation(program_, "projection");
  idBase_ = g.GetUniformLocation(program_, "idBase");
  depthScale_ = g.GetUniformLocation(program_, "depthScale");
  farClip_ = g.GetUniformLocation(program_, "farClip");
  check("building the z-buffer shaders");
}

IdProgram::~IdProgram() {
  if (program_) api().DeleteProgram(program_);
}

void IdProgram::use() const {
  api().UseProgram(program_);
}

void IdProgram::setProjection(const glm::mat4& projection) const {
  api().UniformMatrix4fv(projection_, 1, GL_FALSE, glm::value_ptr(projection));
}

void IdProgram::setDepthScale(float scale) const {
  api().Uniform1f(depthScale_, scale);
}

void IdProgram::setFarClip(float depth) const {
  api().Uniform1f(farClip_, depth);
}

void IdProgram::setModelView(const glm::mat4& modelView) const {
  api().UniformMatrix4fv(modelView_, 1, GL_FALSE, glm::value_ptr(modelView));
}

void IdProgram::setIdBase(uint64_t idBase) const {
  api().Uniform2ui(idBase_, GLuint(idBase), GLuint(idBase >> 32));
}

}  // namespace lzb::gl
