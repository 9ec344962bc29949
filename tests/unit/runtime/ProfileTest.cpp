// User profiles: round trip, atomic save, and clear errors for corrupt files (which leave the model intact).
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/model/UserModel.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

using namespace cbtl;

TEST(Profile, RoundTripKeepsEveryLabel) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  model::UserModel user(lp->graph());
  auto& f = user.generator(0).mutableFactors("seasoning|salt");
  f[0].observe(30, true);
  f[0].observe(34, false);
  f[1].observe(0.97, true);
  const std::string path = (std::filesystem::temp_directory_path() / "cbtl_profile_test.json").string();
  user.save(path);
  model::UserModel loaded(lp->graph());
  loaded.load(path);
  EXPECT_EQ(loaded.toJson(), user.toJson());
  EXPECT_EQ(loaded.dataCount(), 3u);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  std::remove(path.c_str());
}

TEST(Profile, CorruptFilesGiveErrorsWithTheirPath) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok());
  model::UserModel user(lp->graph());
  user.generator(0).mutableFactors("seasoning|salt")[0].observe(30, true);
  const std::string before = user.toJson();
  struct Case {
    const char* text;
    const char* expect;
  };
  const Case cases[] = {
      {"{not json", "not valid JSON"},
      {R"({"format": "other"})", "format"},
      {R"({"format": "cbtl-profile", "version": 2})", "version"},
      {R"({"format": "cbtl-profile", "version": 1, "domain": "books", "generators": {}})", "domain"},
      {R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"nope": {}}})",
       "generators.nope"},
      {R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": {"seasoning|salt": {"temp": {"kind": "interval", "data": [[1, 2]]}, "qty": {"kind": "interval", "data": []}}}}})",
       "temp.data[0]"},
      {R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": {"seasoning|salt": {"temp": {"kind": "interval", "data": []}}}}})",
       "qty: missing factor"},
  };
  for (const auto& c : cases) {
    try {
      user.fromJson(c.text, "p.json");
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const model::ProfileError& e) {
      EXPECT_NE(std::string(e.what()).find("p.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
    EXPECT_EQ(user.toJson(), before) << "a bad profile must leave the model untouched";
  }
  EXPECT_THROW(user.load("/nonexistent/profile.json"), model::ProfileError);
}

namespace {

// A fixed pseudo-random sequence of labelled points over [lo - 1, hi + 1]: liked inside the middle half, with a
// few contradicting labels so that negatives fall between positives (the fit must leave those out).
std::vector<std::pair<double, bool>> samplePoints(std::size_t n, double lo, double hi) {
  std::vector<std::pair<double, bool>> out;
  std::uint64_t s = 7;
  for (std::size_t i = 0; i < n; ++i) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    const double u = static_cast<double>(s >> 11) / static_cast<double>(1ull << 53);
    const double x = lo - 1 + (hi - lo + 2) * u;
    const double q = (x - lo) / (hi - lo);
    const bool liked = (q > 0.25 && q < 0.75) != (i % 17 == 0);
    out.emplace_back(x, liked);
  }
  return out;
}

std::string profileWith(const std::string& key, const std::string& tempFactor) {
  return R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": {")" + key +
         R"(": {"temp": )" + tempFactor + R"(, "qty": {"kind": "interval", "data": []}}}}})";
}

void expectProfileError(model::UserModel& user, const std::string& text, const std::string& expected) {
  const std::string before = user.toJson();
  try {
    user.fromJson(text, "p.json");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const model::ProfileError& e) {
    EXPECT_NE(std::string(e.what()).find("p.json: " + expected), std::string::npos) << e.what();
  }
  EXPECT_EQ(user.toJson(), before) << "a bad profile must leave the model untouched";
}

}  // namespace

TEST(Profile, BulkIntervalFitEqualsPointByPoint) {
  for (std::size_t n : {0u, 1u, 2u, 50u, 3000u}) {
    const auto points = samplePoints(n, 25, 35);
    model::IntervalModel one(25, 35), bulk(25, 35);
    for (const auto& [x, y] : points) one.observe(x, y);
    bulk.observeAll(points);
    EXPECT_EQ(bulk.data(), one.data());
    EXPECT_EQ(bulk.hasPositive(), one.hasPositive());
    EXPECT_EQ(bulk.x1(), one.x1()) << n;
    EXPECT_EQ(bulk.x2(), one.x2()) << n;
    EXPECT_EQ(bulk.x3(), one.x3()) << n;
    EXPECT_EQ(bulk.x4(), one.x4()) << n;
    for (double x = 24; x <= 36; x += 0.125) EXPECT_EQ(bulk.probability(x), one.probability(x)) << n << " at " << x;
  }
}

TEST(Profile, LoadingEqualsObservingPointByPoint) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  model::UserModel direct(lp->graph());
  auto& f = direct.generator(0).mutableFactors("seasoning|salt");
  const auto temp = samplePoints(2000, 25, 35), qty = samplePoints(500, 0.9, 1.1);
  for (const auto& [x, y] : temp) f[0].observe(x, y);
  for (const auto& [x, y] : qty) f[1].observe(x, y);
  const std::string json = direct.toJson();
  model::UserModel loaded(lp->graph());
  loaded.fromJson(json, "p.json");
  EXPECT_EQ(loaded.toJson(), json);  // data and the fitted trapezoids
  EXPECT_EQ(loaded.dataCount(), 2500u);
  const auto& g = loaded.generator(0).factors("seasoning|salt");
  for (double x = 24; x <= 36; x += 0.25) EXPECT_EQ(g[0].probability(x), f[0].probability(x)) << x;
}

TEST(Profile, FactorKindsMustBeTheProgramsDeclaration) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  model::UserModel user(lp->graph());
  user.generator(0).mutableFactors("seasoning|salt")[0].observe(30, true);
  const std::string key = "generators.userEnjoysMeal[\"seasoning|salt\"]";
  expectProfileError(
      user, profileWith("seasoning|salt", R"({"kind": "threshold", "direction": "above", "data": [[30, true]]})"),
      key + ".temp.kind: expected \"interval\"");
  expectProfileError(user, profileWith("seasoning|salt", R"({"kind": "table", "entries": {}})"), key + ".temp.kind");
  expectProfileError(user, profileWith("seasoning|salt", R"({"kind": "text", "backend": "x", "state": {}})"),
                     key + ".temp.kind");
  expectProfileError(user, profileWith("seasoning|salt", R"({"data": []})"), key + ".temp.kind");
  expectProfileError(user, profileWith("seasoning|salt", R"({"kind": 3, "data": []})"), key + ".temp.kind");
  // A factor the generator does not declare.
  expectProfileError(
      user,
      R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": {"seasoning|salt": {"temp": {"kind": "interval", "data": []}, "qty": {"kind": "interval", "data": []}, "salt": {"kind": "interval", "data": []}}}}})",
      key + ".salt: no such factor");
  // The declared kind loads.
  user.fromJson(profileWith("seasoning|salt", R"({"kind": "interval", "data": [[31, true]]})"), "p.json");
  EXPECT_EQ(user.dataCount(), 1u);
}

TEST(Profile, ModelKeysMustHaveTheGeneratorsShape) {
  auto lp = app::LoadedProgram::load(test::cookingPath());
  ASSERT_TRUE(lp->ok()) << lp->errors();
  model::UserModel user(lp->graph());
  const std::string ok = R"({"kind": "interval", "data": []})";
  // per m, ing: two parts.
  expectProfileError(user, profileWith("seasoning", ok),
                     "generators.userEnjoysMeal[\"seasoning\"]: expected 2 '|'-separated parts");
  expectProfileError(user, profileWith("", ok), "generators.userEnjoysMeal[\"\"]: expected 2");
  // m is free text, so a third '|' may belong to it.
  user.fromJson(profileWith("a|b|salt", ok), "p.json");

  // Typed parts: an enum member and a bool; a generator without `per` has only the key "".
  auto typed = test::compileOrFail("k.cbtl", R"(domain k;
enum Color { red, blue }
var c : Color = red;
var on : bool = false;
var x : real in 0 .. 1;
feedback liked(c: Color, on: bool, x: real, ok: bool);
personal likes(c: Color, on: bool, x: real) {
  when c ~ "c", on ~ "on", x ~ "x";
  model interval(x, 0 .. 1) per c, on;
  learn liked(c, on, x, ok) => ok;
}
personal plain(x: real) {
  when x ~ "x";
  model interval(x, 0 .. 1);
  learn liked(_, _, x, ok) => ok;
}
)");
  ASSERT_TRUE(typed->ok());
  model::UserModel k(typed->graph());
  auto profile = [](const std::string& generator, const std::string& key) {
    return R"({"format": "cbtl-profile", "version": 1, "domain": "k", "generators": {")" + generator + R"(": {")" +
           key + R"(": {"interval": {"kind": "interval", "data": [[0.5, true]]}}}}})";
  };
  k.fromJson(profile("likes", "blue|true"), "p.json");
  EXPECT_EQ(k.dataCount(), 1u);
  expectProfileError(k, profile("likes", "green|true"),
                     "generators.likes[\"green|true\"]: part 1 ('green', per c) should be a member of Color");
  expectProfileError(k, profile("likes", "red|yes"),
                     "generators.likes[\"red|yes\"]: part 2 ('yes', per on) should be true or false");
  expectProfileError(k, profile("likes", "red|true|x"),
                     "generators.likes[\"red|true|x\"]: expected 2 '|'-separated parts (per c, on), found 3");
  expectProfileError(k, profile("plain", "x"), "generators.plain[\"x\"]: generator 'plain' has no 'per' keys");
  k.fromJson(profile("plain", ""), "p.json");
}
