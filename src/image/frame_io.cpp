#include "src/image/frame_io.hpp"

// OpenEXR and libpng directly, not OpenImageIO: Debian's libOpenImageIO loads 261 shared
// libraries, 0.35 s at every start of every program linked with it (tests/README.md).
#include <Imath/half.h>
#include <OpenEXR/IexBaseExc.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <png.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"

namespace lzb {
namespace {

// Rows moved per OpenEXR call: a few zip blocks of 16 lines, so large frames never sit whole in
// the native (up to 160 bytes per pixel) layout.
constexpr int kRowsPerBlock = 64;

struct ExrChannel {
  std::string name;
  Imf::PixelType type;
};

size_t bytesOf(Imf::PixelType type) {
  return type == Imf::HALF ? 2 : 4;
}

const char* typeName(Imf::PixelType type) {
  return type == Imf::HALF ? "half" : type == Imf::FLOAT ? "float" : "uint";
}

std::vector<ExrChannel> frameChannels(bool withSubsamples) {
  std::vector<ExrChannel> c = {
      {"R", Imf::HALF},  {"G", Imf::HALF},           {"B", Imf::HALF},           {"A", Imf::HALF},
      {"Z", Imf::FLOAT}, {kIdLowChannel, Imf::UINT}, {kIdHighChannel, Imf::UINT}};
  if (!withSubsamples) return c;
  for (int k = 0; k < kSubsamples; ++k) {
    c.push_back({subsampleIdLowChannel(k), Imf::UINT});
    c.push_back({subsampleIdHighChannel(k), Imf::UINT});
  }
  for (const char* name : kBoxColorChannels) c.push_back({name, Imf::FLOAT});
  return c;
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string() + ": " + what);
}

// Runs an OpenEXR call, reporting its exceptions as bad input naming the file.
template <typename F>
auto exrCall(const std::filesystem::path& path, F&& call) {
  try {
    return call();
  } catch (const Iex::BaseExc& e) {
    fail(path, e.what());
  }
}

// As OpenImageIO did: zip blocks compressed on every core (the bytes do not depend on it).
void useEveryCoreForExr() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(int(std::thread::hardware_concurrency())); });
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

// Slices of `channels` over interleaved rows y0..y1-1 of `width` pixels starting at `block`.
Imf::FrameBuffer interleavedSlices(const std::vector<ExrChannel>& channels, unsigned char* block,
                                   int x0, int y0, int width, int rows) {
  size_t pixelBytes = 0;
  for (const ExrChannel& c : channels) pixelBytes += bytesOf(c.type);
  Imf::FrameBuffer slices;
  size_t offset = 0;
  for (const ExrChannel& c : channels) {
    slices.insert(c.name, Imf::Slice::Make(c.type, block + offset, Imath::V2i(x0, y0), width, rows,
                                           pixelBytes, pixelBytes * size_t(width)));
    offset += bytesOf(c.type);
  }
  return slices;
}

// Writes `header`'s image of `channels` to `tmp` (named like `path`) in blocks of rows filled by
// `fill` in the channels' interleaved layout.
void writeExrImage(const std::filesystem::path& path, const std::filesystem::path& tmp,
                   const Imf::Header& header, const std::vector<ExrChannel>& channels,
                   const std::function<void(int y0, int y1, std::vector<unsigned char>&)>& fill) {
  useEveryCoreForExr();
  const Imath::Box2i window = header.dataWindow();
  const int width = window.max.x + 1, height = window.max.y + 1;
  exrCall(path, [&] {
    Imf::OutputFile out(tmp.c_str(), header);
    std::vector<unsigned char> block;
    for (int y0 = 0; y0 < height; y0 += kRowsPerBlock) {
      const int y1 = std::min(y0 + kRowsPerBlock, height);
      fill(y0, y1, block);
      out.setFrameBuffer(interleavedSlices(channels, block.data(), 0, y0, width, y1 - y0));
      out.writePixels(y1 - y0);
    }
  });
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

// An EXR open for reading in blocks of rows: the channels asked for, interleaved.
class ExrReader {
 public:
  explicit ExrReader(const std::filesystem::path& path)
      : path_(path),
        in_(exrCall(path, [&] { return std::make_unique<Imf::InputFile>(path.c_str()); })) {
    const Imath::Box2i window = in_->header().dataWindow();
    x0_ = window.min.x;
    y0_ = window.min.y;
    width_ = window.max.x - window.min.x + 1;
    height_ = window.max.y - window.min.y + 1;
    if (width_ <= 0 || height_ <= 0) fail(path, "empty image");
  }
  int width() const { return width_; }
  int height() const { return height_; }
  const Imf::Header& header() const { return in_->header(); }
  bool hasChannel(const std::string& name) const {
    return in_->header().channels().findChannel(name) != nullptr;
  }

  // Adds channels to read, found by name (all before any type check: a missing channel is the
  // likelier news) and type-checked: uint32 IDs, half or float otherwise. Returns their indices.
  std::vector<int> channels(const std::vector<std::string>& names, bool isUint) {
    for (const std::string& name : names)
      if (!hasChannel(name)) fail(path_, "missing channel \"" + name + "\"");
    std::vector<int> indices;
    for (const std::string& name : names) {
      const Imf::PixelType t = in_->header().channels().findChannel(name)->type;
      const bool ok = isUint ? t == Imf::UINT : (t == Imf::HALF || t == Imf::FLOAT);
      if (!ok)
        fail(path_, "channel \"" + name + "\" has type " + typeName(t) + ", expected " +
                        (isUint ? "uint" : "half or float"));
      indices.push_back(int(wanted_.size()));
      offsets_.push_back(pixelBytes_);
      wanted_.push_back({name, t});
      pixelBytes_ += bytesOf(t);
    }
    return indices;
  }

  // Calls visit(pixel index) for every pixel, block by block, with the block loaded.
  void forEachPixel(const std::function<void(size_t)>& visit) {
    const size_t width = size_t(width_);
    for (int y0 = 0; y0 < height_; y0 += kRowsPerBlock) {
      const int y1 = std::min(y0 + kRowsPerBlock, height_);
      block_.resize(size_t(y1 - y0) * width * pixelBytes_);
      exrCall(path_, [&] {
        in_->setFrameBuffer(
            interleavedSlices(wanted_, block_.data(), x0_, y0_ + y0, width_, y1 - y0));
        in_->readPixels(y0_ + y0, y0_ + y1 - 1);
      });
      blockStart_ = size_t(y0) * width;
      for (size_t i = blockStart_; i < size_t(y1) * width; ++i) visit(i);
    }
  }
  float asFloat(int c, size_t i) const {
    const unsigned char* p = at(c, i);
    if (wanted_[size_t(c)].type == Imf::HALF) {
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
  std::unique_ptr<Imf::InputFile> in_;
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<ExrChannel> wanted_;
  std::vector<size_t> offsets_;
  size_t pixelBytes_ = 0, blockStart_ = 0;
  std::vector<unsigned char> block_;
};

// The header attributes of FrameOrigin (frame_io.hpp).
constexpr const char* kPositionAttr = "lzb.camera.position";
constexpr const char* kLookAtAttr = "lzb.camera.look_at";
constexpr const char* kUpAttr = "lzb.camera.up";
constexpr const char* kFovAttr = "lzb.camera.fov";
constexpr const char* kNearAttr = "lzb.camera.near";
constexpr const char* kFarAttr = "lzb.camera.far";
constexpr const char* kWidthAttr = "lzb.camera.width";
constexpr const char* kHeightAttr = "lzb.camera.height";
constexpr const char* kTrianglesAttr = "lzb.scene.triangles";
constexpr const char* kOriginAttrs[] = {kPositionAttr, kLookAtAttr, kUpAttr,
                                        kFovAttr,      kNearAttr,   kFarAttr,
                                        kWidthAttr,    kHeightAttr, kTrianglesAttr};

Imath::V3d toV3d(const glm::dvec3& v) {
  return {v.x, v.y, v.z};
}

void putOrigin(Imf::Header& header, const FrameOrigin& origin) {
  const CameraSpec& c = origin.camera.spec();
  header.insert(kPositionAttr, Imf::V3dAttribute(toV3d(c.position)));
  header.insert(kLookAtAttr, Imf::V3dAttribute(toV3d(c.lookAt)));
  header.insert(kUpAttr, Imf::V3dAttribute(toV3d(c.up)));
  header.insert(kFovAttr, Imf::DoubleAttribute(c.fovyDegrees));
  header.insert(kNearAttr, Imf::DoubleAttribute(c.nearPlane));
  header.insert(kFarAttr, Imf::DoubleAttribute(c.farPlane));
  header.insert(kWidthAttr, Imf::IntAttribute(origin.camera.width()));
  header.insert(kHeightAttr, Imf::IntAttribute(origin.camera.height()));
  // A string: uint64 counts beyond 2^53 stay exact.
  header.insert(kTrianglesAttr, Imf::StringAttribute(std::to_string(origin.sceneTriangles)));
}

// The origin's camera must be the frame's: its size is the image's.
void checkOrigin(const Framebuffer& fb, const FrameOrigin* origin,
                 const std::filesystem::path& path) {
  require(!origin || (origin->camera.width() == fb.width && origin->camera.height() == fb.height),
          path.string(), "the camera's size differs from the frame's");
}

// The value of header attribute `name` of OpenEXR type A.
template <typename A>
const auto& attributeOf(const Imf::Header& header, const std::filesystem::path& path,
                        const char* name) {
  const Imf::Header::ConstIterator found = header.find(name);
  if (found == header.end()) fail(path, "missing header attribute \"" + std::string(name) + "\"");
  const A* typed = dynamic_cast<const A*>(&found.attribute());
  if (!typed)
    fail(path, "header attribute \"" + std::string(name) + "\" has type " +
                   found.attribute().typeName() + ", expected " + A::staticTypeName());
  return typed->value();
}

glm::dvec3 getVec3(const Imf::Header& header, const std::filesystem::path& path, const char* name) {
  const Imath::V3d& v = attributeOf<Imf::V3dAttribute>(header, path, name);
  return {v.x, v.y, v.z};
}

uint64_t getCount(const Imf::Header& header, const std::filesystem::path& path, const char* name) {
  const std::string& text = attributeOf<Imf::StringAttribute>(header, path, name);
  const bool digits = !text.empty() && text.size() <= 20 &&
                      text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) fail(path, "header attribute \"" + std::string(name) + "\" is not a count: " + text);
  return std::stoull(text);
}

FrameOrigin originOf(const ExrReader& in, const std::filesystem::path& path) {
  const Imf::Header& h = in.header();
  CameraSpec c;
  c.position = getVec3(h, path, kPositionAttr);
  c.lookAt = getVec3(h, path, kLookAtAttr);
  c.up = getVec3(h, path, kUpAttr);
  c.fovyDegrees = attributeOf<Imf::DoubleAttribute>(h, path, kFovAttr);
  c.nearPlane = attributeOf<Imf::DoubleAttribute>(h, path, kNearAttr);
  c.farPlane = attributeOf<Imf::DoubleAttribute>(h, path, kFarAttr);
  const int width = attributeOf<Imf::IntAttribute>(h, path, kWidthAttr);
  const int height = attributeOf<Imf::IntAttribute>(h, path, kHeightAttr);
  if (width != in.width() || height != in.height())
    fail(path, "header camera is " + std::to_string(width) + "x" + std::to_string(height) +
                   ", the image " + std::to_string(in.width()) + "x" + std::to_string(in.height()));
  return {Camera(c, width, height, path.string() + ": header camera"),
          getCount(h, path, kTrianglesAttr)};
}

void writeExrChannels(const Framebuffer& fb, const ReferenceFrame* sub, const FrameOrigin* origin,
                      const std::filesystem::path& path) {
  const std::vector<ExrChannel> channels = frameChannels(sub != nullptr);
  Imf::Header header(fb.width, fb.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const ExrChannel& c : channels) header.channels().insert(c.name, Imf::Channel(c.type));
  if (origin) putOrigin(header, *origin);
  const auto fill = [&](int y0, int y1, std::vector<unsigned char>& block) {
    RowPacker row(block);
    for (size_t i = fb.index(0, y0); i < fb.index(0, y1); ++i) packPixel(fb, sub, i, row);
  };
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    writeExrImage(path, tmp, header, channels, fill);
  });
}

// fb's colour as R, G, B, A bytes per pixel: the framebuffer's own memory where Rgba8's byte
// order is that (color.hpp packs R in the low byte), a copy otherwise.
const unsigned char* rgbaBytes(const Framebuffer& fb, std::vector<unsigned char>& copy) {
  if constexpr (std::endian::native == std::endian::little)
    return reinterpret_cast<const unsigned char*>(fb.color.data());
  copy.clear();
  for (Rgba8 c : fb.color)
    for (int k = 0; k < 4; ++k) copy.push_back(channel(c, k));
  return copy.data();
}

// An 8-bit RGBA PNG, straight alpha (libpng's 8-bit formats are not premultiplied).
void writePngImage(const Framebuffer& fb, const std::filesystem::path& path,
                   const std::filesystem::path& tmp) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = png_uint_32(fb.width);
  image.height = png_uint_32(fb.height);
  image.format = PNG_FORMAT_RGBA;
  std::vector<unsigned char> copy;
  if (!png_image_write_to_file(&image, tmp.c_str(), 0, rgbaBytes(fb, copy), 0, nullptr))
    fail(path, image.message);
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
  writeFileAtomically(path,
                      [&](const std::filesystem::path& tmp) { writePngImage(fb, path, tmp); });
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

  Framebuffer fb(in.width(), in.height());
  in.forEachPixel([&](size_t i) {
    fb.color[i] = packRgba8(
        unitToByteExact(in.asFloat(colour[0], i)), unitToByteExact(in.asFloat(colour[1], i)),
        unitToByteExact(in.asFloat(colour[2], i)), unitToByteExact(in.asFloat(colour[3], i)));
    fb.depth[i] = in.asFloat(colour[4], i);
    fb.id[i] = in.asId(id[0], id[1], i);
  });
  return fb;
}

ReferenceFrame readReferenceExr(const std::filesystem::path& path) {
  ExrReader in(path);
  if (!in.hasChannel(subsampleIdLowChannel(0)))
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

  ReferenceFrame ref(in.width(), in.height());
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
  for (const char* name : kOriginAttrs)
    if (in.header().find(name) != in.header().end()) return originOf(in, path);
  return std::nullopt;
}

}  // namespace lzb
