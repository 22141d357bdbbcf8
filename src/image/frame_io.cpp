#include "src/image/frame_io.hpp"

#include <OpenImageIO/half.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
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

// Rows moved per OIIO call: a few zip blocks of 16 lines, so large frames never sit whole in
// the native (up to 160 bytes per pixel) layout.
constexpr int kRowsPerBlock = 64;

struct ExrChannel {
  std::string name;
  TypeDesc type;
};

std::vector<ExrChannel> frameChannels(bool withSubsamples) {
  std::vector<ExrChannel> c = {{"R", TypeDesc::HALF},   {"G", TypeDesc::HALF},
                               {"B", TypeDesc::HALF},   {"A", TypeDesc::HALF},
                               {"Z", TypeDesc::FLOAT},  {kIdLowChannel, TypeDesc::UINT32},
                               {kIdHighChannel, TypeDesc::UINT32}};
  if (!withSubsamples) return c;
  for (int k = 0; k < kSubsamples; ++k) {
    c.push_back({subsampleIdLowChannel(k), TypeDesc::UINT32});
    c.push_back({subsampleIdHighChannel(k), TypeDesc::UINT32});
  }
  for (const char* name : kBoxColorChannels) c.push_back({name, TypeDesc::FLOAT});
  return c;
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string() + ": " + what);
}

// OIIO reports errors through the object or, when no object was made, globally.
std::string oiioError(const std::string& objectError) {
  if (!objectError.empty()) return objectError;
  std::string global = OIIO::geterror();
  return global.empty() ? "unknown OpenImageIO error" : global;
}

// Appends pixel values in the EXR's native per-channel layout.
class RowPacker {
 public:
  explicit RowPacker(std::vector<unsigned char>& bytes) : bytes_(bytes) { bytes_.clear(); }
  template <typename T>
  void put(T value) {
    const size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &value, sizeof(T));
  }
  void putId(uint64_t id) {
    put(uint32_t(id));
    put(uint32_t(id >> 32));
  }

 private:
  std::vector<unsigned char>& bytes_;
};

float byteToUnit(uint8_t v) {
  return float(v) / 255.0f;
}

uint8_t unitToByteExact(float v) {
  if (!(v >= 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  return uint8_t(std::lround(v * 255.0f));
}

// Box colours are means of 16 bytes: back to the nearest 1/16 of a byte unit.
float unitToBoxMean(float v) {
  const float sixteenths = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f * float(kSubsamples));
  return sixteenths / float(kSubsamples);
}

// Pixel i of fb (and of the sub-sample data, when given) in frameChannels' order.
void packPixel(const Framebuffer& fb, const ReferenceFrame* sub, size_t i, RowPacker& row) {
  const Rgba8 c = fb.color[i];
  for (int k = 0; k < 4; ++k) row.put(Imath::half(byteToUnit(channel(c, k))));
  row.put(fb.depth[i]);
  row.putId(fb.id[i]);
  if (!sub) return;
  const uint64_t* ids = sub->subsamples(i);
  for (int k = 0; k < kSubsamples; ++k) row.putId(ids[k]);
  for (float mean : sub->boxColor[i]) row.put(mean / 255.0f);
}

// Writes the image to `tmp` (named like `path`) in blocks of rows filled by `fill`.
void writeImage(const std::filesystem::path& path, const std::filesystem::path& tmp,
                const ImageSpec& spec,
                const std::function<void(int y0, int y1, std::vector<unsigned char>&)>& fill) {
  auto out = ImageOutput::create(tmp.string());
  if (!out) fail(path, oiioError(""));
  if (!out->open(tmp.string(), spec)) fail(path, oiioError(out->geterror()));
  std::vector<unsigned char> block;
  bool written = true;
  for (int y0 = 0; y0 < spec.height && written; y0 += kRowsPerBlock) {
    const int y1 = std::min(y0 + kRowsPerBlock, spec.height);
    fill(y0, y1, block);
    // TypeUnknown: the buffer is in the spec's native per-channel formats.
    written = out->write_scanlines(y0, y1, 0, TypeDesc::UNKNOWN, block.data());
  }
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

int channelIndex(const ImageSpec& spec, const std::string& name) {
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelnames[size_t(c)] == name) return c;
  return -1;
}

int findChannel(const ImageSpec& spec, const std::filesystem::path& path, const std::string& name) {
  const int c = channelIndex(spec, name);
  if (c < 0) fail(path, "missing channel \"" + name + "\"");
  return c;
}

// An EXR open for reading in blocks of rows, each in the native per-channel layout.
class ExrReader {
 public:
  explicit ExrReader(const std::filesystem::path& path) : path_(path) {
    in_ = ImageInput::open(path.string());
    if (!in_) fail(path, oiioError(""));
    spec_ = in_->spec();
    if (spec_.deep || spec_.depth != 1) fail(path, "not a flat 2-D image");
    if (spec_.width <= 0 || spec_.height <= 0) fail(path, "empty image");
    pixelBytes_ = spec_.pixel_bytes(true);
    size_t offset = 0;
    for (int c = 0; c < spec_.nchannels; ++c) {
      offsets_.push_back(offset);
      offset += spec_.channelformat(c).size();
    }
  }
  const ImageSpec& spec() const { return spec_; }

  // Finds channels by name (all before any type check: a missing channel is the likelier news)
  // and checks their types: uint32 IDs, half or float otherwise.
  std::vector<int> channels(const std::vector<std::string>& names, bool isUint) const {
    std::vector<int> found;
    for (const std::string& name : names) found.push_back(findChannel(spec_, path_, name));
    for (size_t k = 0; k < names.size(); ++k) {
      const TypeDesc f = spec_.channelformat(found[k]);
      const bool ok =
          isUint ? f == TypeDesc::UINT32 : (f == TypeDesc::HALF || f == TypeDesc::FLOAT);
      if (!ok)
        fail(path_, "channel \"" + names[k] + "\" has type " + f.c_str() + ", expected " +
                        (isUint ? "uint" : "half or float"));
    }
    return found;
  }

  // Calls visit(pixel index) for every pixel, block by block, with the block loaded.
  void forEachPixel(const std::function<void(size_t)>& visit) {
    const size_t width = size_t(spec_.width);
    for (int y0 = 0; y0 < spec_.height; y0 += kRowsPerBlock) {
      const int y1 = std::min(y0 + kRowsPerBlock, spec_.height);
      block_.resize(size_t(y1 - y0) * width * pixelBytes_);
      if (!in_->read_scanlines(0, 0, y0, y1, 0, 0, spec_.nchannels, TypeDesc::UNKNOWN,
                               block_.data()))
        fail(path_, oiioError(in_->geterror()));
      blockStart_ = size_t(y0) * width;
      for (size_t i = blockStart_; i < size_t(y1) * width; ++i) visit(i);
    }
  }
  float asFloat(int c, size_t i) const {
    const unsigned char* p = at(c, i);
    if (spec_.channelformat(c) == TypeDesc::HALF) {
      Imath::half h;
      std::memcpy(&h, p, sizeof(h));
      return float(h);
    }
    float f;
    std::memcpy(&f, p, sizeof(f));
    return f;
  }
  uint64_t asId(int low, int high, size_t i) const {
    uint32_t lo, hi;
    std::memcpy(&lo, at(low, i), sizeof(lo));
    std::memcpy(&hi, at(high, i), sizeof(hi));
    return uint64_t(hi) << 32 | lo;
  }

 private:
  const unsigned char* at(int c, size_t i) const {
    return block_.data() + (i - blockStart_) * pixelBytes_ + offsets_[size_t(c)];
  }
  std::filesystem::path path_;
  std::unique_ptr<ImageInput> in_;
  ImageSpec spec_;
  size_t pixelBytes_ = 0, blockStart_ = 0;
  std::vector<size_t> offsets_;
  std::vector<unsigned char> block_;
};

// The header attributes of FrameOrigin (frame_io.hpp).
const TypeDesc kVec3d(TypeDesc::DOUBLE, TypeDesc::VEC3);
constexpr const char* kPositionAttr = "lzb.camera.position";
constexpr const char* kLookAtAttr = "lzb.camera.look_at";
constexpr const char* kUpAttr = "lzb.camera.up";
constexpr const char* kFovAttr = "lzb.camera.fov";
constexpr const char* kNearAttr = "lzb.camera.near";
constexpr const char* kFarAttr = "lzb.camera.far";
constexpr const char* kWidthAttr = "lzb.camera.width";
constexpr const char* kHeightAttr = "lzb.camera.height";
constexpr const char* kTrianglesAttr = "lzb.scene.triangles";
constexpr const char* kOriginAttrs[] = {kPositionAttr, kLookAtAttr, kUpAttr,    kFovAttr,
                                        kNearAttr,     kFarAttr,    kWidthAttr, kHeightAttr,
                                        kTrianglesAttr};

void putVec3(ImageSpec& spec, const char* name, const glm::dvec3& v) {
  const double xyz[3] = {v.x, v.y, v.z};
  spec.attribute(name, kVec3d, xyz);
}

void putOrigin(ImageSpec& spec, const FrameOrigin& origin) {
  const CameraSpec& c = origin.camera.spec();
  putVec3(spec, kPositionAttr, c.position);
  putVec3(spec, kLookAtAttr, c.lookAt);
  putVec3(spec, kUpAttr, c.up);
  spec.attribute(kFovAttr, TypeDesc::DOUBLE, &c.fovyDegrees);
  spec.attribute(kNearAttr, TypeDesc::DOUBLE, &c.nearPlane);
  spec.attribute(kFarAttr, TypeDesc::DOUBLE, &c.farPlane);
  spec.attribute(kWidthAttr, origin.camera.width());
  spec.attribute(kHeightAttr, origin.camera.height());
  // A string: uint64 counts beyond 2^53 stay exact.
  spec.attribute(kTrianglesAttr, std::to_string(origin.sceneTriangles));
}

// The origin's camera must be the frame's: its size is the image's.
void checkOrigin(const Framebuffer& fb, const FrameOrigin* origin, const std::filesystem::path& path) {
  require(!origin || (origin->camera.width() == fb.width && origin->camera.height() == fb.height),
          path.string(), "the camera's size differs from the frame's");
}

// The attribute `name` of `type` (semantics aside: OpenEXR reads a v3d back as a vector).
const OIIO::ParamValue& attributeOf(const ImageSpec& spec, const std::filesystem::path& path,
                                    const char* name, TypeDesc type) {
  const OIIO::ParamValue* p = spec.find_attribute(name);
  if (!p) fail(path, "missing header attribute \"" + std::string(name) + "\"");
  const TypeDesc t = p->type();
  if (t.basetype != type.basetype || t.aggregate != type.aggregate || t.arraylen != type.arraylen)
    fail(path, "header attribute \"" + std::string(name) + "\" has type " + t.c_str() +
                   ", expected " + type.c_str());
  return *p;
}

glm::dvec3 getVec3(const ImageSpec& spec, const std::filesystem::path& path, const char* name) {
  const double* xyz = static_cast<const double*>(attributeOf(spec, path, name, kVec3d).data());
  return {xyz[0], xyz[1], xyz[2]};
}

double getDouble(const ImageSpec& spec, const std::filesystem::path& path, const char* name) {
  return *static_cast<const double*>(attributeOf(spec, path, name, TypeDesc::DOUBLE).data());
}

int getInt(const ImageSpec& spec, const std::filesystem::path& path, const char* name) {
  return *static_cast<const int*>(attributeOf(spec, path, name, TypeDesc::INT).data());
}

uint64_t getCount(const ImageSpec& spec, const std::filesystem::path& path, const char* name) {
  const OIIO::ParamValue& p = attributeOf(spec, path, name, TypeDesc::STRING);
  const std::string text = p.get_string();
  const bool digits = !text.empty() && text.size() <= 20 &&
                      text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) fail(path, "header attribute \"" + std::string(name) + "\" is not a count: " + text);
  return std::stoull(text);
}

FrameOrigin originOf(const ImageSpec& spec, const std::filesystem::path& path) {
  CameraSpec c;
  c.position = getVec3(spec, path, kPositionAttr);
  c.lookAt = getVec3(spec, path, kLookAtAttr);
  c.up = getVec3(spec, path, kUpAttr);
  c.fovyDegrees = getDouble(spec, path, kFovAttr);
  c.nearPlane = getDouble(spec, path, kNearAttr);
  c.farPlane = getDouble(spec, path, kFarAttr);
  const int width = getInt(spec, path, kWidthAttr), height = getInt(spec, path, kHeightAttr);
  if (width != spec.width || height != spec.height)
    fail(path, "header camera is " + std::to_string(width) + "x" + std::to_string(height) +
                   ", the image " + std::to_string(spec.width) + "x" + std::to_string(spec.height));
  return {Camera(c, width, height, path.string() + ": header camera"),
          getCount(spec, path, kTrianglesAttr)};
}

void writeExrChannels(const Framebuffer& fb, const ReferenceFrame* sub, const FrameOrigin* origin,
                      const std::filesystem::path& path) {
  const std::vector<ExrChannel> channels = frameChannels(sub != nullptr);
  ImageSpec spec(fb.width, fb.height, int(channels.size()), TypeDesc::HALF);
  spec.channelnames.clear();
  spec.channelformats.clear();
  for (const ExrChannel& c : channels) {
    spec.channelnames.push_back(c.name);
    spec.channelformats.push_back(c.type);
  }
  spec.alpha_channel = 3;
  spec.z_channel = 4;
  spec.attribute("compression", "zip");
  // No capture date: identical frames must give identical files (the 2-rank test compares bytes).
  spec.attribute("DateTime", "");
  if (origin) putOrigin(spec, *origin);
  const auto fill = [&](int y0, int y1, std::vector<unsigned char>& block) {
    RowPacker row(block);
    for (size_t i = fb.index(0, y0); i < fb.index(0, y1); ++i) packPixel(fb, sub, i, row);
  };
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    writeImage(path, tmp, spec, fill);
  });
}

}  // namespace

std::string subsampleIdLowChannel(int k) {
  return "sub.ID." + std::to_string(k);
}

std::string subsampleIdHighChannel(int k) {
  return "sub.ID.hi." + std::to_string(k);
}

std::string frameStem(int frame) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "frame_%04d", frame);
  return buf;
}

void writeExr(const Framebuffer& fb, const std::filesystem::path& path, const FrameOrigin* origin) {
  checkOrigin(fb, origin, path);
  writeExrChannels(fb, nullptr, origin, path);
}

void writeExr(const Framebuffer& fb, const ReferenceFrame& subsamples,
              const std::filesystem::path& path, const FrameOrigin* origin) {
  require(subsamples.width == fb.width && subsamples.height == fb.height, path.string(),
          "the sub-sample data's size differs from the frame's");
  checkOrigin(fb, origin, path);
  writeExrChannels(fb, &subsamples, origin, path);
}

void writePng(const Framebuffer& fb, const std::filesystem::path& path) {
  ImageSpec spec(fb.width, fb.height, 4, TypeDesc::UINT8);
  spec.alpha_channel = 3;
  // Our colour is not premultiplied: keep OIIO from dividing it by alpha on the way out.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  const auto fill = [&](int y0, int y1, std::vector<unsigned char>& block) {
    block.clear();
    for (size_t i = fb.index(0, y0); i < fb.index(0, y1); ++i)
      for (int k = 0; k < 4; ++k) block.push_back(channel(fb.color[i], k));
  };
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    writeImage(path, tmp, spec, fill);
  });
}

void writeFrame(const Framebuffer& fb, const std::filesystem::path& dir, int frame,
                const ReferenceFrame* subsamples, const FrameOrigin* origin) {
  require(fb.width > 0 && fb.height > 0, dir.string(), "cannot write an empty frame");
  require(frame >= 0, dir.string(), "frame number " + std::to_string(frame) + " is negative");
  const std::string stem = frameStem(frame);
  if (subsamples) {
    writeExr(fb, *subsamples, dir / (stem + ".exr"), origin);
  } else {
    writeExr(fb, dir / (stem + ".exr"), origin);
  }
  writePng(fb, dir / (stem + ".png"));
}

Framebuffer readFrameExr(const std::filesystem::path& path) {
  ExrReader in(path);
  const std::vector<int> colour = in.channels({"R", "G", "B", "A", "Z"}, false);
  const std::vector<int> id = in.channels({kIdLowChannel, kIdHighChannel}, true);

  Framebuffer fb(in.spec().width, in.spec().height);
  in.forEachPixel([&](size_t i) {
    fb.color[i] = packRgba8(unitToByteExact(in.asFloat(colour[0], i)),
                            unitToByteExact(in.asFloat(colour[1], i)),
                            unitToByteExact(in.asFloat(colour[2], i)),
                            unitToByteExact(in.asFloat(colour[3], i)));
    fb.depth[i] = in.asFloat(colour[4], i);
    fb.id[i] = in.asId(id[0], id[1], i);
  });
  return fb;
}

ReferenceFrame readReferenceExr(const std::filesystem::path& path) {
  ExrReader in(path);
  if (channelIndex(in.spec(), subsampleIdLowChannel(0)) < 0)
    fail(path, "has no sub-sample channels (\"" + subsampleIdLowChannel(0) +
                   "\" ...): render the reference with `lzb render --subsamples`");
  std::vector<std::string> idNames = {kIdLowChannel, kIdHighChannel};
  for (int k = 0; k < kSubsamples; ++k) {
    idNames.push_back(subsampleIdLowChannel(k));
    idNames.push_back(subsampleIdHighChannel(k));
  }
  const std::vector<int> id = in.channels(idNames, true);  // centre, then sub-sample pairs
  const std::vector<int> box =
      in.channels({kBoxColorChannels[0], kBoxColorChannels[1], kBoxColorChannels[2]}, false);

  ReferenceFrame ref(in.spec().width, in.spec().height);
  in.forEachPixel([&](size_t i) {
    ref.centreId[i] = in.asId(id[0], id[1], i);
    for (size_t k = 0; k < size_t(kSubsamples); ++k)
      ref.subsampleId[i * kSubsamples + k] = in.asId(id[2 + 2 * k], id[3 + 2 * k], i);
    for (size_t c = 0; c < 3; ++c) ref.boxColor[i][c] = unitToBoxMean(in.asFloat(box[c], i));
  });
  return ref;
}

std::optional<FrameOrigin> readFrameOrigin(const std::filesystem::path& path) {
  const ExrReader in(path);
  const ImageSpec& spec = in.spec();
  for (const char* name : kOriginAttrs)
    if (spec.find_attribute(name)) return originOf(spec, path);
  return std::nullopt;
}

}  // namespace lzb
