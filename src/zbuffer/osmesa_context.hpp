#pragma once
// An OSMesa (Mesa llvmpipe) OpenGL 4.5 core-profile context. It renders only into framebuffer
// objects, so its own window buffer is a 1x1 placeholder.
#include <array>
#include <cstdint>
#include <string>

namespace lzb::gl {

class OsMesaContext {
 public:
  // llvmpipe sizes its thread pool from LP_NUM_THREADS when Mesa first creates its screen.
  OsMesaContext();
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  // Binds the context to the calling thread (cheap when it already is); call before GL work.
  void makeCurrent();
  // "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string description() const { return description_; }

 private:
  void* context_ = nullptr;  // OSMesaContext, kept opaque so callers need not include osmesa.h
  std::array<uint8_t, 4> placeholder_{};
  std::string description_;
};

}  // namespace lzb::gl
