#include "src/image/frame_io.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/image/compare.hpp"

namespace lzb {
namespace {

namespace fs = std::filesystem;

// A fresh empty directory per test, removed afterwards.
class FrameIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        fs::temp_directory_path() / ("lzb_image_" + std::to_string(getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

// Every byte value, depths incl. +inf, IDs incl. > 2^32 and kNoId.
Framebuffer sampleFrame() {
  Framebuffer fb(37, 23);
  for (size_t i = 0; i < fb.size(); ++i) {
    if (i % 5 == 0) continue;  // empty: kBackground, +inf, kNoId
    const uint8_t v = uint8_t(i * 7);
    fb.color[i] = packRgba8(v, uint8_t(255 - v), uint8_t(i), uint8_t(i % 3 == 0 ? 255 : v));
    fb.depth[i] = 0.001f * float(i) + 1e-7f;
    fb.id[i] = (uint64_t(i) << 33) + 0xfffffff0ull + i;
  }
  fb.depth[1] = std::numeric_limits<float>::max();
  fb.id[1] = kNoId - 1;
  fb.id[2] = 0;
  fb.id[3] = 0xffffffffull;  // low half equal to kNoId's
  return fb;
}

void expectSameFrame(const Framebuffer& a, const Framebuffer& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.color[i], b.color[i]) << "pixel " << i;
    ASSERT_EQ(a.id[i], b.id[i]) << "pixel " << i;
    ASSERT_TRUE(a.depth[i] == b.depth[i])
        << "pixel " << i << ": " << a.depth[i] << " vs " << b.depth[i];
  }
}

TEST_F(FrameIoTest, FrameStemPadsToFourDigits) {
  EXPECT_EQ(frameStem(7), "frame_0007");
  EXPECT_EQ(frameStem(12345), "frame_12345");
}

TEST_F(FrameIoTest, ExrRoundTripIsExact) {
  const Framebuffer fb = sampleFrame();
  writeFrame(fb, dir_, 3);
  EXPECT_EQ(entries(), (std::vector<std::string>{"frame_0003.exr", "frame_0003.png"}));
  const Framebuffer back = readFrameExr(dir_ / "frame_0003.exr");
  expectSameFrame(fb, back);
  EXPECT_TRUE(std::isinf(back.depth[0]) && back.depth[0] > 0);
  EXPECT_EQ(back.id[0], kNoId);
  EXPECT_EQ(back.id[1], kNoId - 1);
  EXPECT_EQ(back.id[3], 0xffffffffull);
}

TEST_F(FrameIoTest, ExrChannelsAreNamedAndTyped) {
  writeFrame(sampleFrame(), dir_, 0);
  auto in = OIIO::ImageInput::open((dir_ / "frame_0000.exr").string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::map<std::string, OIIO::TypeDesc> formats;
  for (int c = 0; c < spec.nchannels; ++c)
    formats[spec.channelnames[size_t(c)]] = spec.channelformat(c);
  ASSERT_EQ(formats.size(), 7u);
  EXPECT_EQ(formats.at("R"), OIIO::TypeDesc::HALF);
  EXPECT_EQ(formats.at("A"), OIIO::TypeDesc::HALF);
  EXPECT_EQ(formats.at("Z"), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(formats.at("ID"), OIIO::TypeDesc::UINT32);
  EXPECT_EQ(formats.at("ID.hi"), OIIO::TypeDesc::UINT32);
}

TEST_F(FrameIoTest, PngHoldsTheColourBytes) {
  const Framebuffer fb = sampleFrame();
  writeFrame(fb, dir_, 12);
  // Ask for the bytes as stored: OIIO would otherwise premultiply them by alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open((dir_ / "frame_0012.png").string(), &config);
  ASSERT_TRUE(in);
  ASSERT_EQ(in->spec().nchannels, 4);
  ASSERT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> bytes(4 * fb.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, bytes.data()));
  for (size_t i = 0; i < fb.size(); ++i)
    for (int k = 0; k < 4; ++k)
      ASSERT_EQ(bytes[4 * i + size_t(k)], channel(fb.color[i], k)) << "pixel " << i << " ch " << k;
  EXPECT_EQ(bytes[3], 0);  // background alpha
}

TEST_F(FrameIoTest, OverwritesAnExistingFrame) {
  Framebuffer fb = sampleFrame();
  writeFrame(fb, dir_, 1);
  fb.id[7] = 42;
  writeFrame(fb, dir_, 1);
  EXPECT_EQ(readFrameExr(dir_ / "frame_0001.exr").id[7], 42u);
  EXPECT_EQ(entries().size(), 2u);
}

TEST_F(FrameIoTest, MissingDirectoryThrowsAndCreatesNothing) {
  const fs::path missing = dir_ / "no" / "such";
  try {
    writeFrame(sampleFrame(), missing, 0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame_0000.exr"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "no"));
  EXPECT_TRUE(entries().empty());
}

TEST_F(FrameIoTest, DirectoryThatIsAFileThrows) {
  std::ofstream(dir_ / "plain") << "x";
  EXPECT_THROW(writeFrame(sampleFrame(), dir_ / "plain", 0), InputError);
  EXPECT_EQ(entries(), std::vector<std::string>{"plain"});
}

TEST_F(FrameIoTest, UnwritableDirectoryThrowsAndLeavesNothing) {
  if (geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path locked = dir_ / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_THROW(writeFrame(sampleFrame(), locked, 0), InputError);
  fs::permissions(locked, fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(locked));
}

TEST_F(FrameIoTest, FailedRenameLeavesNoTemporary) {
  // A non-empty directory squats on the EXR's name: the temporary is written, the rename fails.
  fs::create_directories(dir_ / "frame_0000.exr" / "keep");
  try {
    writeFrame(sampleFrame(), dir_, 0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame_0000.exr"), std::string::npos) << e.what();
  }
  // Neither a temporary nor the PNG (the EXR goes first).
  EXPECT_EQ(entries(), std::vector<std::string>{"frame_0000.exr"});
}

TEST_F(FrameIoTest, MissingFileThrowsNamingIt) {
  const fs::path path = dir_ / "absent.exr";
  try {
    readFrameExr(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST_F(FrameIoTest, GarbageFileThrowsNamingIt) {
  const fs::path path = dir_ / "garbage.exr";
  std::ofstream(path, std::ios::binary) << "this is not an OpenEXR file at all";
  try {
    readFrameExr(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST_F(FrameIoTest, TruncatedFileThrows) {
  writeFrame(sampleFrame(), dir_, 0);
  const fs::path path = dir_ / "frame_0000.exr";
  fs::resize_file(path, fs::file_size(path) / 2);
  EXPECT_THROW(readFrameExr(path), InputError);
}

TEST_F(FrameIoTest, MissingIdChannelIsNamed) {
  // An ordinary RGBA + Z EXR, as another tool would write it.
  const fs::path path = dir_ / "plain.exr";
  OIIO::ImageSpec spec(4, 3, 5, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B", "A", "Z"};
  std::vector<float> pixels(4 * 3 * 5, 0.5f);
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out && out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  out->close();
  try {
    readFrameExr(path);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find("\"ID\""), std::string::npos) << what;
  }
}

TEST_F(FrameIoTest, PngIsNotAFrameExr) {
  writeFrame(sampleFrame(), dir_, 0);
  const fs::path png = dir_ / "frame_0000.png";
  try {
    readFrameExr(png);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(png.string() + ": ", 0), 0u) << what;
    EXPECT_NE(what.find("not an image file"), std::string::npos) << what;
  }
}

// sampleFrame's reference data: sub-sample IDs around the centre's (incl. > 2^32 and kNoId) and
// box colours on every sixteenth of a byte, up to 255.
ReferenceFrame sampleReference(const Framebuffer& fb) {
  ReferenceFrame ref(fb.width, fb.height);
  ref.centreId = fb.id;
  for (size_t i = 0; i < ref.size(); ++i) {
    for (int k = 0; k < kSubsamples; ++k)
      ref.subsampleId[i * kSubsamples + size_t(k)] = k == 5 ? kNoId : fb.id[i] + uint64_t(k) * (1ull << 32);
    for (int c = 0; c < 3; ++c)
      ref.boxColor[i][size_t(c)] = float((i * 37 + size_t(c) * 1361) % 4081) / 16.0f;
  }
  ref.boxColor[0] = {255.0f, 254.9375f, 0.0625f};
  return ref;
}

TEST_F(FrameIoTest, SubsampleChannelsRoundTripExactly) {
  const Framebuffer fb = sampleFrame();
  const ReferenceFrame ref = sampleReference(fb);
  writeFrame(fb, dir_, 4, &ref);
  const fs::path exr = dir_ / "frame_0004.exr";
  expectSameFrame(fb, readFrameExr(exr));  // the plain reader still reads it
  const ReferenceFrame back = readReferenceExr(exr);
  ASSERT_EQ(back.width, fb.width);
  ASSERT_EQ(back.height, fb.height);
  EXPECT_EQ(back.centreId, ref.centreId);
  EXPECT_EQ(back.subsampleId, ref.subsampleId);
  for (size_t i = 0; i < ref.size(); ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(back.boxColor[i][size_t(c)], ref.boxColor[i][size_t(c)]) << i << " " << c;
}

TEST_F(FrameIoTest, SubsampleChannelsAreNamedAndTyped) {
  const Framebuffer fb = sampleFrame();
  const ReferenceFrame ref = sampleReference(fb);
  writeFrame(fb, dir_, 0, &ref);
  auto in = OIIO::ImageInput::open((dir_ / "frame_0000.exr").string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::map<std::string, OIIO::TypeDesc> formats;
  for (int c = 0; c < spec.nchannels; ++c)
    formats[spec.channelnames[size_t(c)]] = spec.channelformat(c);
  ASSERT_EQ(formats.size(), 7u + 32u + 3u);
  EXPECT_EQ(formats.at("sub.ID.0"), OIIO::TypeDesc::UINT32);
  EXPECT_EQ(formats.at("sub.ID.hi.15"), OIIO::TypeDesc::UINT32);
  EXPECT_EQ(formats.at("R.aa"), OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(formats.at("B.aa"), OIIO::TypeDesc::FLOAT);
}

TEST_F(FrameIoTest, PlainFrameIsNotAReference) {
  writeFrame(sampleFrame(), dir_, 0);
  const fs::path exr = dir_ / "frame_0000.exr";
  try {
    readReferenceExr(exr);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(exr.string()), std::string::npos) << what;
    EXPECT_NE(what.find("--subsamples"), std::string::npos) << what;
  }
}

TEST_F(FrameIoTest, CompareFilesOfAFrameWithItsOwnReferenceIsCorrect) {
  const Framebuffer fb = sampleFrame();
  const ReferenceFrame ref = sampleReference(fb);
  writeFrame(fb, dir_, 0, &ref);
  const fs::path exr = dir_ / "frame_0000.exr";
  const nlohmann::json j = compareFiles(exr, exr);
  EXPECT_EQ(j.at("correct_rate_covered"), 1.0);
  EXPECT_EQ(j.at("exact_id_rate_covered"), 1.0);
  EXPECT_EQ(j.at("pixels"), fb.size());
  // The colours are the frame's, not the box filter's: a finite PSNR.
  EXPECT_GT(j.at("rmse_aa").get<double>(), 0.0);
  EXPECT_FALSE(j.at("psnr_aa").is_null());
}

TEST_F(FrameIoTest, CompareFilesOfDifferentSizesNamesBoth) {
  writeFrame(sampleFrame(), dir_, 0);
  const Framebuffer small(5, 5);
  const ReferenceFrame smallRef = sampleReference(small);
  writeFrame(small, dir_, 1, &smallRef);
  const fs::path a = dir_ / "frame_0000.exr", b = dir_ / "frame_0001.exr";
  try {
    compareFiles(a, b);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(a.string()), std::string::npos) << what;
    EXPECT_NE(what.find(b.string()), std::string::npos) << what;
  }
}

// A camera whose every field needs all of a double's bits, for a 37 x 23 frame.
FrameOrigin sampleOrigin(uint64_t triangles = (1ull << 60) + 3) {
  CameraSpec c;
  c.position = {1e7 + 1.0 / 3.0, -2.0 / 7.0, 0.1};
  c.lookAt = {std::nextafter(1e7, 0.0), 5.0 / 11.0, -1e-9};
  c.up = {0.1, 1.0 / 3.0, 0.7};
  c.fovyDegrees = 45.0 / 7.0;
  c.nearPlane = 1e-3 / 3.0;
  c.farPlane = 1e5 / 7.0;
  return {Camera(c, 37, 23), triangles};
}

void expectSameOrigin(const FrameOrigin& a, const FrameOrigin& b) {
  const CameraSpec &p = a.camera.spec(), &q = b.camera.spec();
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(p.position[k], q.position[k]);
    EXPECT_EQ(p.lookAt[k], q.lookAt[k]);
    EXPECT_EQ(p.up[k], q.up[k]);
  }
  EXPECT_EQ(p.fovyDegrees, q.fovyDegrees);
  EXPECT_EQ(p.nearPlane, q.nearPlane);
  EXPECT_EQ(p.farPlane, q.farPlane);
  EXPECT_EQ(a.camera.width(), b.camera.width());
  EXPECT_EQ(a.camera.height(), b.camera.height());
  EXPECT_EQ(a.sceneTriangles, b.sceneTriangles);
  // The rebuilt camera casts the same rays.
  EXPECT_EQ(a.camera.pixelDirection(3.25, 7.5), b.camera.pixelDirection(3.25, 7.5));
}

TEST_F(FrameIoTest, TheCameraRoundTripsExactlyInTheHeader) {
  const Framebuffer fb = sampleFrame();
  const ReferenceFrame ref = sampleReference(fb);
  const FrameOrigin origin = sampleOrigin();
  writeFrame(fb, dir_, 0, nullptr, &origin);
  writeFrame(fb, dir_, 1, &ref, &origin);
  for (const char* name : {"frame_0000.exr", "frame_0001.exr"}) {
    const std::optional<FrameOrigin> back = readFrameOrigin(dir_ / name);
    ASSERT_TRUE(back.has_value()) << name;
    expectSameOrigin(*back, origin);
    EXPECT_TRUE(sameOrigin(*back, origin));
  }
  expectSameFrame(fb, readFrameExr(dir_ / "frame_0000.exr"));
}

TEST_F(FrameIoTest, AFrameWithoutOriginHasNone) {
  writeFrame(sampleFrame(), dir_, 0);
  EXPECT_FALSE(readFrameOrigin(dir_ / "frame_0000.exr").has_value());
}

TEST_F(FrameIoTest, AnOriginOfAnotherSizeIsRefusedAndNothingWritten) {
  const Framebuffer small(5, 5);
  const FrameOrigin origin = sampleOrigin();
  EXPECT_THROW(writeFrame(small, dir_, 0, nullptr, &origin), InputError);
  EXPECT_TRUE(entries().empty());
}

// An EXR with some of the header attributes, as a hand-edited file might be.
void writePartialHeader(const fs::path& path, bool withWrongType) {
  OIIO::ImageSpec spec(4, 3, 1, OIIO::TypeDesc::FLOAT);
  const double xyz[3] = {0.0, 0.0, 5.0};
  spec.attribute("lzb.camera.position", OIIO::TypeDesc(OIIO::TypeDesc::DOUBLE, OIIO::TypeDesc::VEC3), xyz);
  if (withWrongType) spec.attribute("lzb.camera.look_at", 3.5f);
  std::vector<float> pixels(12, 0.0f);
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out && out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
  out->close();
}

TEST_F(FrameIoTest, AnIncompleteOrMistypedHeaderIsNamed) {
  const fs::path partial = dir_ / "partial.exr", typed = dir_ / "typed.exr";
  writePartialHeader(partial, false);
  writePartialHeader(typed, true);
  for (const auto& [path, attribute] : {std::pair{partial, "lzb.camera.look_at"},
                                        std::pair{typed, "lzb.camera.look_at"}}) {
    try {
      readFrameOrigin(path);
      FAIL() << "expected InputError for " << path;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path.string()), std::string::npos) << what;
      EXPECT_NE(what.find(attribute), std::string::npos) << what;
    }
  }
}

TEST_F(FrameIoTest, CompareFilesRefusesFramesOfDifferentCameras) {
  const Framebuffer fb = sampleFrame();
  const ReferenceFrame ref = sampleReference(fb);
  const FrameOrigin a = sampleOrigin(), other = sampleOrigin(12);
  writeFrame(fb, dir_, 0, nullptr, &a);
  writeFrame(fb, dir_, 1, &ref, &other);
  writeFrame(fb, dir_, 2, &ref, &a);
  const fs::path test = dir_ / "frame_0000.exr", wrong = dir_ / "frame_0001.exr";
  try {
    compareFiles(test, wrong);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(test.string()), std::string::npos) << what;
    EXPECT_NE(what.find(wrong.string()), std::string::npos) << what;
  }
  EXPECT_EQ(compareFiles(test, dir_ / "frame_0002.exr").at("witness"), "none");
}

}  // namespace
}  // namespace lzb
