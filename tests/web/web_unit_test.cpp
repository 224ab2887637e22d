// stepmod-web's pieces that need no browser: the instance port rule, the access token and
// sessions, the cookie parser, the page's module description.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "web/auth.hpp"
#include "web/image_json.hpp"
#include "web/options.hpp"

namespace stepmod::web {
namespace {

std::string token_file(const std::string& content) {
  char path[] = "/tmp/stepmod-web-token-XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  std::ofstream(path) << content;
  close(fd);
  return path;
}

TEST(WebPort, IsBasePlusTheNamesTrailingNumber) {
  EXPECT_EQ(default_port("stepmod"), 8610u);
  EXPECT_EQ(default_port("press2"), 8612u);
  EXPECT_EQ(default_port("line17"), 8627u);
  EXPECT_EQ(default_port("3601-board"), 8610u);  // the digits must end the name
  EXPECT_THROW(default_port("axis1234"), std::invalid_argument);
}

TEST(WebCookie, FindsTheSessionAmongOthers) {
  EXPECT_EQ(cookie_value("a=1; stepmod_web=abc; b=2", "stepmod_web"), "abc");
  EXPECT_EQ(cookie_value("stepmod_web=xyz", "stepmod_web"), "xyz");
  EXPECT_EQ(cookie_value("stepmod_web_old=1", "stepmod_web"), "");
  EXPECT_EQ(cookie_value(nullptr, "stepmod_web"), "");
}

TEST(WebAuth, TheTokenMakesASessionAndNothingElseDoes) {
  const std::string f = token_file("0123456789abcdef0123\n");
  Auth auth(f);
  EXPECT_EQ(auth.login("wrong-token-wrong-token"), "");
  EXPECT_EQ(auth.login("0123456789abcdef012"), "");  // a prefix is not the token
  const std::string id = auth.login(" 0123456789abcdef0123\n");
  ASSERT_EQ(id.size(), 64u);
  EXPECT_TRUE(auth.valid(("stepmod_web=" + id).c_str()));
  EXPECT_FALSE(auth.valid("stepmod_web=0000"));
  EXPECT_FALSE(auth.valid(nullptr));
  EXPECT_NE(auth.login("0123456789abcdef0123"), id);  // every login its own session
  std::remove(f.c_str());
}

TEST(WebAuth, RefusesAMissingOrShortToken) {
  EXPECT_THROW(Auth("/nonexistent/stepmod-web-token"), std::runtime_error);
  const std::string f = token_file("short\n");
  EXPECT_THROW(Auth{f}, std::runtime_error);
  std::remove(f.c_str());
}

TEST(WebModule, DescribesThe3602WithItsConfigurationBitsAndRanges) {
  const auto j = module_json(ModuleType::k3602);
  EXPECT_EQ(j["type"], 3602);
  EXPECT_EQ(j["units"], 2);
  EXPECT_FALSE(j["config_bits"]["msw"].empty());
  EXPECT_GT(j["ranges"]["speed_max"].get<int>(), 0);
  EXPECT_LE(j["ranges"]["accel_min"].get<int>(), j["ranges"]["accel_max"].get<int>());
}

// The 3202: two channels, one configuration DINT with the manual's bits (the form sends it whole),
// rates in steps/s^2 with the manual's range.
TEST(WebModule, DescribesThe3202WithItsConfigurationDintAndRanges) {
  const auto j = module_json(ModuleType::k3202);
  EXPECT_EQ(j["type"], 3202);
  EXPECT_EQ(j["units"], 2);
  ASSERT_TRUE(j["config_bits"].contains("dint"));
  EXPECT_FALSE(j["config_bits"].contains("msw"));
  bool disable = false;
  for (const auto& b : j["config_bits"]["dint"]) disable |= b["bit"] == 28;
  EXPECT_TRUE(disable);
  EXPECT_EQ(j["ranges"]["accel_min"], 1'000);
  EXPECT_EQ(j["ranges"]["accel_max"], 2'000'000);
  EXPECT_EQ(j["ranges"]["accel_unit"], "steps/s²");
  EXPECT_EQ(j["ranges"]["target_max"], 8'388'607);
  EXPECT_EQ(module_json(ModuleType::k3601)["ranges"]["accel_unit"], "steps/ms/s");
}

TEST(WebModule, UnitShowsEveryNamedStatusBit) {
  ImageWords in;
  in.w[0] = 0x4001;  // 3601 status MSW: Moving CW, Module OK
  const auto j = unit_json(ModuleType::k3601, in, 0);
  int set = 0;
  for (const auto& b : j["words"][0]["bits"]) {
    if (b["value"] == 1) {
      ++set;
      EXPECT_TRUE(b["name"] == "Moving CW" || b["name"] == "Module OK") << b["name"];
    }
  }
  EXPECT_EQ(set, 2);
  EXPECT_EQ(j["words"][0]["bits"].size(), 16u);
}

}  // namespace
}  // namespace stepmod::web
