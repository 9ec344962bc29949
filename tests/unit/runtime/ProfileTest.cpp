// User profiles: round trip, atomic save, and clear errors for corrupt files (which leave the model intact).
#include "TestPrograms.h"

#include "UserModel.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace cbtl;

TEST(Profile, RoundTripKeepsEveryLabel) {
  auto lp = approach::LoadedProgram::load(test::cookingPath());
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
  auto lp = approach::LoadedProgram::load(test::cookingPath());
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
      {R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"nope": {}}})", "generators.nope"},
      {R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": {"k": {"temp": {"data": [[1, 2]]}, "qty": {"data": []}}}}})",
       "temp.data[0]"},
      {R"({"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": {"k": {"temp": {"data": []}}}}})",
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
