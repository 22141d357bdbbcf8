#include "src/zbuffer/gl_api.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace lzb::gl {

namespace {

Api load() {
  Api a;
  // OSMesa's dispatch entry points do not depend on the current context, so one table serves all.
#define LZB_GL_LOAD(name)                                                        \
  a.name = reinterpret_cast<decltype(a.name)>(OSMesaGetProcAddress("gl" #name)); \
  if (!a.name) throw std::runtime_error("OSMesa does not provide gl" #name);
  LZB_GL_FUNCTIONS(LZB_GL_LOAD)
#undef LZB_GL_LOAD
  return a;
}

}  // namespace

const Api& api() {
  static const Api table = load();
  return table;
}

void check(const char* what) {
  const GLenum e = api().GetError();
  if (e == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof(code), "0x%04X", unsigned(e));
  throw std::runtime_error(std::string(what) + ": GL error " + code);
}

}  // namespace lzb::gl
