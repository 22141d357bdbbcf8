#pragma once
// The OpenGL 4.5 core entry points the z-buffer uses, fetched through OSMesaGetProcAddress
// (libOSMesa does not export every core function, e.g. glClipControl, as a linkable symbol). The
// one place GL headers are included: glcorearb.h must come before osmesa.h (which pulls in the
// legacy gl.h) for the core prototypes to be declared.
#define GL_GLEXT_PROTOTYPES 1  // only so decltype(&::glFoo) names each function's type
#include <GL/glcorearb.h>
#include <GL/osmesa.h>

namespace lzb::gl {

// X(name): glName is stored as member `name`.
// clang-format off
#define LZB_GL_FUNCTIONS(X)                                                                       \
  X(GetString) X(GetError) X(GetIntegerv) X(Enable) X(Disable) X(DepthFunc) X(DepthMask)        \
  X(Viewport) X(Finish) X(ReadPixels) X(PixelStorei) X(ReadBuffer) X(DrawBuffers) X(ClipControl) \
  X(GenFramebuffers) X(DeleteFramebuffers) X(BindFramebuffer) X(FramebufferRenderbuffer)        \
  X(CheckFramebufferStatus) X(GenRenderbuffers) X(DeleteRenderbuffers) X(BindRenderbuffer)      \
  X(RenderbufferStorage) X(ClearBufferuiv) X(ClearBufferfv) X(CreateShader) X(ShaderSource)     \
  X(CompileShader) X(GetShaderiv) X(GetShaderInfoLog) X(DeleteShader) X(CreateProgram)          \
  X(AttachShader) X(LinkProgram) X(GetProgramiv) X(GetProgramInfoLog) X(DeleteProgram)          \
  X(UseProgram) X(GetUniformLocation) X(UniformMatrix4fv) X(Uniform2ui) X(Uniform1f)           \
  X(GenVertexArrays) X(DeleteVertexArrays) X(BindVertexArray) X(GenBuffers) X(DeleteBuffers)    \
  X(BindBuffer) X(BufferData) X(EnableVertexAttribArray) X(VertexAttribPointer) X(DrawArrays)     \
  X(DrawElements) X(Flush)
// clang-format on

struct Api {
#define LZB_GL_MEMBER(name) decltype(&::gl##name) name = nullptr;
  LZB_GL_FUNCTIONS(LZB_GL_MEMBER)
#undef LZB_GL_MEMBER
};

// The entry points, loaded on first use; throws std::runtime_error naming a missing one.
const Api& api();

// Throws std::runtime_error("<what>: GL error 0x...") when glGetError reports one.
void check(const char* what);

}  // namespace lzb::gl
