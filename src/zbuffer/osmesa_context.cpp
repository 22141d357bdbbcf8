#include "src/zbuffer/osmesa_context.hpp"

#include <stdexcept>

#include "src/zbuffer/gl_api.hpp"

namespace lzb::gl {

OsMesaContext::OsMesaContext() {
  // 4.5 core: glClipControl (reversed-Z), float depth and integer colour attachments.
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         4,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         5,
                         0};
  context_ = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!context_)
    throw std::runtime_error("OSMesa could not create an OpenGL 4.5 core-profile context");
  makeCurrent();
  const Api& g = api();
  description_ = std::string(reinterpret_cast<const char*>(g.GetString(GL_VERSION))) + ", " +
                 reinterpret_cast<const char*>(g.GetString(GL_RENDERER));
}

OsMesaContext::~OsMesaContext() {
  if (context_) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OsMesaContext::makeCurrent() {
  if (OSMesaGetCurrentContext() == static_cast<OSMesaContext>(context_)) return;
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), placeholder_.data(),
                         GL_UNSIGNED_BYTE, 1, 1))
    throw std::runtime_error("OSMesaMakeCurrent failed");
}

}  // namespace lzb::gl
