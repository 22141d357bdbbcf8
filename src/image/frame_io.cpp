#include "src/image/frame_io.hpp"

#include <OpenImageIO/half.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <vector>

#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"

namespace lzb {
namespace {

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

// One EXR pixel in its native (per-channel) layout, packed as OIIO expects it.
struct ExrPixel {
  Imath::half r, g, b, a;
  float z;
  uint32_t idLow, idHigh;
};
static_assert(sizeof(ExrPixel) == 20, "EXR pixel must be packed without padding");

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string() + ": " + what);
}

// OIIO reports errors through the object or, when no object was made, globally.
std::string oiioError(const std::string& objectError) {
  if (!objectError.empty()) return objectError;
  std::string global = OIIO::geterror();
  return global.empty() ? "unknown OpenImageIO error" : global;
}

// Opens `tmp` (named like `path`) for writing, writes `pixels` in `format` and closes it.
void writeImage(const std::filesystem::path& path, const std::filesystem::path& tmp,
                const ImageSpec& spec, TypeDesc format, const void* pixels) {
  auto out = ImageOutput::create(tmp.string());
  if (!out) fail(path, oiioError(""));
  if (!out->open(tmp.string(), spec)) fail(path, oiioError(out->geterror()));
  const bool written = out->write_image(format, pixels);
  const bool closed = out->close();
  if (!written || !closed) fail(path, oiioError(out->geterror()));
}

// writeAtomically, with a failed rename also reported as bad input naming the file.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write) {
  try {
    writeAtomically(path, write);
  } catch (const std::filesystem::filesystem_error& e) {
    fail(path, e.code().message());
  }
}

float byteToUnit(uint8_t v) {
  return float(v) / 255.0f;
}

uint8_t unitToByteExact(float v) {
  if (!(v >= 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  return uint8_t(std::lround(v * 255.0f));
}

int findChannel(const ImageSpec& spec, const std::filesystem::path& path, const char* name) {
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelnames[size_t(c)] == name) return c;
  fail(path, std::string("missing channel \"") + name + "\"");
}

// Reads channel `c` of the native pixel buffer as float (half or float channels).
class ChannelReader {
 public:
  ChannelReader(const ImageSpec& spec, const std::vector<unsigned char>& pixels, size_t pixelBytes)
      : spec_(spec), pixels_(pixels), pixelBytes_(pixelBytes) {
    offsets_.resize(size_t(spec.nchannels));
    size_t offset = 0;
    for (int c = 0; c < spec.nchannels; ++c) {
      offsets_[size_t(c)] = offset;
      offset += spec.channelformat(c).size();
    }
  }
  TypeDesc format(int c) const { return spec_.channelformat(c); }
  float asFloat(int c, size_t i) const {
    const unsigned char* p = pixels_.data() + i * pixelBytes_ + offsets_[size_t(c)];
    if (format(c) == TypeDesc::HALF) {
      Imath::half h;
      std::memcpy(&h, p, sizeof(h));
      return float(h);
    }
    float f;
    std::memcpy(&f, p, sizeof(f));
    return f;
  }
  uint32_t asUint(int c, size_t i) const {
    uint32_t u;
    std::memcpy(&u, pixels_.data() + i * pixelBytes_ + offsets_[size_t(c)], sizeof(u));
    return u;
  }

 private:
  const ImageSpec& spec_;
  const std::vector<unsigned char>& pixels_;
  size_t pixelBytes_;
  std::vector<size_t> offsets_;
};

void requireFormat(const ChannelReader& reader, int c, const std::filesystem::path& path,
                   const char* name, bool isUint) {
  const TypeDesc f = reader.format(c);
  const bool ok = isUint ? f == TypeDesc::UINT32 : (f == TypeDesc::HALF || f == TypeDesc::FLOAT);
  if (!ok)
    fail(path, std::string("channel \"") + name + "\" has type " + f.c_str() + ", expected " +
                   (isUint ? "uint" : "half or float"));
}

}  // namespace

std::string frameStem(int frame) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "frame_%04d", frame);
  return buf;
}

void writeExr(const Framebuffer& fb, const std::filesystem::path& path) {
  ImageSpec spec(fb.width, fb.height, 7, TypeDesc::HALF);
  spec.channelnames = {"R", "G", "B", "A", "Z", kIdLowChannel, kIdHighChannel};
  spec.channelformats = {TypeDesc::HALF,  TypeDesc::HALF,   TypeDesc::HALF,  TypeDesc::HALF,
                         TypeDesc::FLOAT, TypeDesc::UINT32, TypeDesc::UINT32};
  spec.alpha_channel = 3;
  spec.z_channel = 4;
  spec.attribute("compression", "zip");
  // No capture date: identical frames must give identical files (the 2-rank test compares bytes).
  spec.attribute("DateTime", "");
  std::vector<ExrPixel> pixels(fb.size());
  for (size_t i = 0; i < fb.size(); ++i) {
    const Rgba8 c = fb.color[i];
    pixels[i] = {Imath::half(byteToUnit(channel(c, 0))),
                 Imath::half(byteToUnit(channel(c, 1))),
                 Imath::half(byteToUnit(channel(c, 2))),
                 Imath::half(byteToUnit(channel(c, 3))),
                 fb.depth[i],
                 uint32_t(fb.id[i]),
                 uint32_t(fb.id[i] >> 32)};
  }
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    // TypeUnknown: the buffer is in the spec's native per-channel formats.
    writeImage(path, tmp, spec, TypeDesc::UNKNOWN, pixels.data());
  });
}

void writePng(const Framebuffer& fb, const std::filesystem::path& path) {
  ImageSpec spec(fb.width, fb.height, 4, TypeDesc::UINT8);
  spec.alpha_channel = 3;
  // Our colour is not premultiplied: keep OIIO from dividing it by alpha on the way out.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  std::vector<uint8_t> bytes(4 * fb.size());
  for (size_t i = 0; i < fb.size(); ++i)
    for (int k = 0; k < 4; ++k) bytes[4 * i + size_t(k)] = channel(fb.color[i], k);
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    writeImage(path, tmp, spec, TypeDesc::UINT8, bytes.data());
  });
}

void writeFrame(const Framebuffer& fb, const std::filesystem::path& dir, int frame) {
  require(fb.width > 0 && fb.height > 0, dir.string(), "cannot write an empty frame");
  require(frame >= 0, dir.string(), "frame number " + std::to_string(frame) + " is negative");
  const std::string stem = frameStem(frame);
  writeExr(fb, dir / (stem + ".exr"));
  writePng(fb, dir / (stem + ".png"));
}

Framebuffer readFrameExr(const std::filesystem::path& path) {
  auto in = ImageInput::open(path.string());
  if (!in) fail(path, oiioError(""));
  const ImageSpec spec = in->spec();
  if (spec.deep || spec.depth != 1) fail(path, "not a flat 2-D image");
  if (spec.width <= 0 || spec.height <= 0) fail(path, "empty image");
  const char* names[] = {"R", "G", "B", "A", "Z", kIdLowChannel, kIdHighChannel};
  int ch[7];
  for (int k = 0; k < 7; ++k) ch[k] = findChannel(spec, path, names[k]);

  const size_t pixelBytes = spec.pixel_bytes(true);
  std::vector<unsigned char> pixels(size_t(spec.width) * size_t(spec.height) * pixelBytes);
  if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::UNKNOWN, pixels.data()))
    fail(path, oiioError(in->geterror()));
  in->close();

  ChannelReader reader(spec, pixels, pixelBytes);
  for (int k = 0; k < 7; ++k) requireFormat(reader, ch[k], path, names[k], k >= 5);

  Framebuffer fb(spec.width, spec.height);
  for (size_t i = 0; i < fb.size(); ++i) {
    fb.color[i] = packRgba8(
        unitToByteExact(reader.asFloat(ch[0], i)), unitToByteExact(reader.asFloat(ch[1], i)),
        unitToByteExact(reader.asFloat(ch[2], i)), unitToByteExact(reader.asFloat(ch[3], i)));
    fb.depth[i] = reader.asFloat(ch[4], i);
    fb.id[i] = uint64_t(reader.asUint(ch[6], i)) << 32 | reader.asUint(ch[5], i);
  }
  return fb;
}

}  // namespace lzb
