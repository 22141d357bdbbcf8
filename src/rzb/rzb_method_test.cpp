// The rzb options: out-of-range values are InputErrors naming the option (exit status 2 in lzb).
#include "src/rzb/rzb_method.hpp"

#include <gtest/gtest.h>

#include "src/core/error.hpp"

namespace lzb::rzb {
namespace {

std::string errorOf(const std::string& eps, double oversample, int splat, const std::string& fallback,
                    const std::string& reconstruct, double ratio, double cache,
                    const std::string& backfaces = "drop") {
  try {
    parseRzbOptions(eps, oversample, splat, fallback, reconstruct, ratio, cache, backfaces);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RzbOptions, DefaultsParse) {
  const RzbParams p = parseRzbOptions("1.5", 1.0, 1, "auto", "auto", 4.0, 0.0, "drop");
  EXPECT_EQ(p.eps, 1.5);
  EXPECT_EQ(p.reconstruct, Reconstruct::kPixel);
  EXPECT_TRUE(p.fallback);
  EXPECT_EQ(p.fallbackRender, FallbackRender::kNative);
  EXPECT_EQ(parseRzbOptions("1.5", 1.0, 1, "auto", "auto", 4.0, 0.0, "drop", "gl").fallbackRender,
            FallbackRender::kGl);
  EXPECT_TRUE(parseRzbOptions("auto", 1.0, 3, "off", "auto", 8.0, 64.0, "keep").autoEps);
  EXPECT_EQ(parseRzbOptions("2", 1.0, 3, "off", "auto", 8.0, 0.0, "keep").reconstruct,
            Reconstruct::kSplat);
  EXPECT_EQ(parseRzbOptions("2", 1.0, 1, "12.5", "gauss", 8.0, 0.0, "drop").fallbackPx, 12.5);
}

TEST(RzbOptions, OutOfRangeValuesNameTheOption) {
  EXPECT_NE(errorOf("1", 1, 1, "auto", "auto", 4, 0).find("--eps"), std::string::npos);
  EXPECT_NE(errorOf("0.5", 1, 1, "auto", "auto", 4, 0).find("--eps"), std::string::npos);
  EXPECT_NE(errorOf("fast", 1, 1, "auto", "auto", 4, 0).find("--eps"), std::string::npos);
  EXPECT_NE(errorOf("1.5", -1, 1, "auto", "auto", 4, 0).find("--oversample"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 0, 1, "auto", "auto", 4, 0).find("--oversample"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 0, "auto", "auto", 4, 0).find("--splat"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 2, "auto", "pixel", 4, 0).find("--reconstruct"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "auto", "nice", 4, 0).find("--reconstruct"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "-3", "auto", 4, 0).find("--fallback"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "lots", "auto", 4, 0).find("--fallback"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "auto", "auto", 1, 0).find("--area-ratio"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "auto", "auto", 65, 0).find("--area-ratio"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "auto", "auto", 4, -1).find("--cache-mb"), std::string::npos);
  EXPECT_NE(errorOf("1.5", 1, 1, "auto", "auto", 4, 0, "maybe").find("--backfaces"),
            std::string::npos);
  try {
    parseRzbOptions("1.5", 1.0, 1, "auto", "auto", 4.0, 0.0, "drop", "opengl");
    ADD_FAILURE() << "--fallback-render opengl accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--fallback-render"), std::string::npos);
  }
}

TEST(RzbOptions, MethodRegistersItsOptions) {
  const std::unique_ptr<Method> method = makeRzbMethod();
  EXPECT_EQ(method->name(), "rzb");
  EXPECT_FALSE(method->exact());
  CLI::App app;
  method->addOptions(app);
  const char* argv[] = {"x", "--eps", "2.5", "--splat", "2", "--cache-mb", "32",
                        "--fallback-render", "gl"};
  app.parse(9, const_cast<char**>(argv));
  method->validate();
  const nlohmann::json j = method->parameters();
  EXPECT_EQ(j["eps"].get<double>(), 2.5);
  EXPECT_EQ(j["splat"].get<int>(), 2);
  EXPECT_EQ(j["reconstruct"].get<std::string>(), "splat");
  EXPECT_EQ(j["cache_mb"].get<double>(), 32.0);
  EXPECT_EQ(j["fallback_render"].get<std::string>(), "gl");
}

}  // namespace
}  // namespace lzb::rzb
