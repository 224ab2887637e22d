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
#include "web/path_request.hpp"
#include "web/reason_help.hpp"
#include "web/sim_inputs.hpp"

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

TEST(WebAuth, LogoutEndsTheSessionOnly) {
  const std::string f = token_file("0123456789abcdef0123\n");
  Auth auth(f);
  const std::string a = "stepmod_web=" + auth.login("0123456789abcdef0123");
  const std::string b = "stepmod_web=" + auth.login("0123456789abcdef0123");
  EXPECT_TRUE(auth.logout(a.c_str()));
  EXPECT_FALSE(auth.valid(a.c_str()));
  EXPECT_TRUE(auth.valid(b.c_str()));  // another browser's session stays
  EXPECT_FALSE(auth.logout(a.c_str()));
  EXPECT_FALSE(auth.logout(nullptr));
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
  // The two-bit CW/CCW input function (limit or E-stop) is one field the page offers whole.
  int two_bit = 0;
  for (const auto& b : j["config_bits"]["msw"]) two_bit += b.value("width", 1) == 2;
  EXPECT_EQ(two_bit, 2);
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

// Issue 32: a reason's full condition, what to do and its anchor, for every code the page can see.
TEST(WebReasons, EveryItemHasItsConditionAndAFix) {
  const auto t = reason_table(ModuleType::k3601);
  ASSERT_TRUE(t.contains("10401"));  // 3601-IE-01, the E-stop
  EXPECT_EQ(t["10401"]["id"], "3601-IE-01");
  EXPECT_EQ(t["10401"]["condition"], "the E-stop input activated");
  EXPECT_NE(t["10401"]["fix"].get<std::string>().find("E-stop"), std::string::npos);
  EXPECT_TRUE(t.contains("10200"));  // each list's own code, the fallback of unlisted items
  for (const auto& [code, row] : t.items()) {
    EXPECT_FALSE(row["fix"].get<std::string>().empty()) << code;
    EXPECT_FALSE(row["condition"].get<std::string>().empty()) << code;
  }
  // The 3602's path items and shared items numbered alike (3602-CE-10) keep every condition.
  const auto t2 = reason_table(ModuleType::k3602);
  EXPECT_EQ(t2["20267"]["id"], "3602-CE-I7");
  EXPECT_NE(t2["20210"]["condition"].get<std::string>().find(";"), std::string::npos);
  EXPECT_NE(reasons_page(ModuleType::k3602).find("id=\"3602-CE-I7\""), std::string::npos);
}

TEST(WebReasons, RatesAreGivenInTheFormsUnit) {
  EXPECT_EQ(in_form_units("3601-CE-04: accel 5000000 or decel 100000 steps/s2 out of", 1000),
            "3601-CE-04: accel 5000 or decel 100 steps/ms/s out of");
  EXPECT_EQ(in_form_units("accel 1500 or decel 2 steps/s2", 1000),
            "accel 1.5 or decel 0.002 steps/ms/s");
  EXPECT_EQ(in_form_units("accel 500 or decel 100000 steps/s2 out of range", 1),
            "accel 500 or decel 100000 steps/s2 out of range");  // the 3202's form: steps/s2
  EXPECT_EQ(in_form_units("3601-CE-05: Vp 500 is below Vs 1000", 1000),
            "3601-CE-05: Vp 500 is below Vs 1000");
}

TEST(WebModule, HelloNamesTheConsoleProcessAndTheReasons) {
  const auto h = hello_json("m", ModuleType::k3202);
  EXPECT_EQ(h["type"], "hello");
  EXPECT_EQ(h["console"]["pid"].get<long long>(), static_cast<long long>(getpid()));
  EXPECT_GT(h["console"]["started_ms"].get<long long>(), 0);
  EXPECT_EQ(h["reasons"]["30401"]["id"], "3202-IE-01");
}

// Issue 32: the page's 3602 paths, each field checked before anything is written.
TEST(WebPath, ARequestBecomesTheManualsMove) {
  const auto req = nlohmann::json::parse(
      R"({"cmd": "path", "unit": 0, "method": "centre", "sense": "ccw", "absolute": false,
          "end_x": 0, "end_y": 0, "point_x": 2000, "point_y": 0, "speed": 6000, "accel": 20,
          "decel": 20, "profile": 0})");
  const plc::PathMove3602 m = path_request(req);
  EXPECT_EQ(m.method, plc::PathMove3602::Method::kCentreCcw);
  EXPECT_EQ(m.point_x, 2000);
  EXPECT_EQ(m.profile.speed, 6000);
  auto line = req;
  line["method"] = "line";
  line["end_x"] = -5;
  EXPECT_EQ(path_request(line).method, plc::PathMove3602::Method::kLinear);
  EXPECT_EQ(path_request(line).end_x, -5);
}

TEST(WebPath, BadFieldsAreRefusedByName) {
  const auto ok = nlohmann::json::parse(
      R"({"method": "radius", "sense": "cw", "absolute": true, "end_x": 10, "end_y": 10,
          "radius": 100, "speed": 1000, "accel": 20, "decel": 20, "profile": 0})");
  EXPECT_NO_THROW(path_request(ok));
  const auto refused = [&](const char* key, const nlohmann::json& value, const char* says) {
    auto r = ok;
    if (value.is_null())
      r.erase(key);
    else
      r[key] = value;
    try {
      path_request(r);
      ADD_FAILURE() << key << " taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  refused("method", "spiral", "method");
  refused("sense", "up", "sense");
  refused("radius", nullptr, "radius");
  refused("radius", 3'000'000'000LL, "radius");
  refused("end_x", "12", "end_x");
  refused("absolute", 1, "absolute");
  refused("accel", -1, "accel");
  refused("profile", 3, "profile");
}

// Without a simulated machine (real hardware, or no daemon) nothing is shown and a force is
// refused, never attempted.
TEST(WebSimInputs, WithoutAPanelNothingIsShownOrForced) {
  SimInputs sim("webunit-no-such-module");
  EXPECT_FALSE(sim.present());
  EXPECT_TRUE(sim.state().is_null());
  const auto req = nlohmann::json::parse(R"({"unit": 0, "input": "estop", "level": 1})");
  EXPECT_THROW(sim.force(req), std::invalid_argument);
}

}  // namespace
}  // namespace stepmod::web
