// The MJCF name reader of check-world: bodies and geoms by name, includes relative to the including file, defaults
// and unnamed elements left out, and each way a world cannot be read reported with its file, line and include chain.
#include "compiler/world/WorldNames.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
class WorldNamesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cbtl-world-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }

  fs::path dir_;
};

TEST_F(WorldNamesTest, BodiesAndGeomsByNameThroughIncludes) {
  const std::string scene = write("scene.xml", R"(<mujoco>
  <default>
    <geom contype="1"/>
    <default class="soft"><geom name="template_geom" margin="0.01"/></default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1"/>
    <body name="user">
      <geom name="user_torso" type="sphere" size="0.1"/>
      <body><geom name="user_hand" type="sphere" size="0.05"/></body>
      <body name=""><geom type="sphere" size="0.05"/></body>
    </body>
    <body name="mount">
      <include file="robots/arm.xml"/>
    </body>
  </worldbody>
</mujoco>
)");
  write("robots/arm.xml", R"(<mujoco>
  <body name="base_link"><geom name="base_geom" type="sphere" size="0.1"/>
    <include file="../parts/gripper.xml"/>
  </body>
</mujoco>
)");
  write("parts/gripper.xml",
        R"(<mujoco><body name="gripper"><geom name="finger" type="box" size="1 1 1"/></body></mujoco>)");
  const WorldReadResult r = readWorldNames(scene);
  ASSERT_TRUE(r.ok) << r.error.file << ":" << r.error.line << ": " << r.error.message;
  EXPECT_EQ(r.names.bodies, (std::set<std::string>{"base_link", "gripper", "mount", "user"}));
  EXPECT_EQ(r.names.geoms, (std::set<std::string>{"base_geom", "finger", "floor", "user_hand", "user_torso"}));
  EXPECT_EQ(r.names.geomBody.at("user_torso"), "user");
  EXPECT_EQ(r.names.geomBody.at("user_hand"), "");  // its body has no name
  EXPECT_EQ(r.names.geomBody.at("floor"), "");
  EXPECT_EQ(r.names.geomBody.at("finger"), "gripper");
  ASSERT_EQ(r.names.files.size(), 3u);
  EXPECT_EQ(r.names.files[0], scene);
  EXPECT_EQ(fs::path(r.names.files[1]).filename(), "arm.xml");
  EXPECT_EQ(fs::path(r.names.files[2]), (dir_ / "parts" / "gripper.xml").lexically_normal());
}

TEST_F(WorldNamesTest, AMissingSceneIsUnreadable) {
  const WorldReadResult r = readWorldNames((dir_ / "nowhere.xml").string());
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Unreadable);
  EXPECT_EQ(r.error.line, 0);
  EXPECT_EQ(r.error.message, "no such file");
  EXPECT_TRUE(r.error.includedFrom.empty());
  EXPECT_TRUE(r.names.bodies.empty());
}

TEST_F(WorldNamesTest, AFolderIsNotAScene) {
  const WorldReadResult r = readWorldNames(dir_.string());
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Unreadable);
}

TEST_F(WorldNamesTest, MalformedXmlGivesExpatsMessageAndLine) {
  const std::string scene =
      write("scene.xml", "<mujoco>\n  <worldbody>\n    <body name=\"a\">\n  </worldbody>\n</mujoco>\n");
  const WorldReadResult r = readWorldNames(scene);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Malformed);
  EXPECT_EQ(r.error.file, scene);
  EXPECT_EQ(r.error.line, 4);
  EXPECT_EQ(r.error.message, "mismatched tag");
}

TEST_F(WorldNamesTest, AnEmptyFileIsNotXml) {
  const WorldReadResult r = readWorldNames(write("scene.xml", ""));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Malformed);
}

TEST_F(WorldNamesTest, AnErrorInAnIncludedFileNamesTheChain) {
  const std::string scene =
      write("scene.xml", "<mujoco>\n  <worldbody>\n    <include file=\"arm.xml\"/>\n  </worldbody>\n</mujoco>\n");
  write("arm.xml", "<mujoco>\n\n  <include file=\"sub/hand.xml\"/>\n</mujoco>\n");
  write("sub/hand.xml", "<mujoco><body name=\"x\"></mujoco>");
  const WorldReadResult r = readWorldNames(scene);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Malformed);
  EXPECT_EQ(fs::path(r.error.file), (dir_ / "sub" / "hand.xml").lexically_normal());
  EXPECT_EQ(r.error.line, 1);
  ASSERT_EQ(r.error.includedFrom.size(), 2u);
  EXPECT_EQ(r.error.includedFrom[0], std::make_pair(scene, 3));
  EXPECT_EQ(fs::path(r.error.includedFrom[1].first).filename(), "arm.xml");
  EXPECT_EQ(r.error.includedFrom[1].second, 3);
}

TEST_F(WorldNamesTest, AMissingIncludeIsUnreadable) {
  const std::string scene = write("scene.xml", "<mujoco>\n  <include file=\"gone.xml\"/>\n</mujoco>\n");
  const WorldReadResult r = readWorldNames(scene);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Unreadable);
  EXPECT_EQ(fs::path(r.error.file).filename(), "gone.xml");
  ASSERT_EQ(r.error.includedFrom.size(), 1u);
  EXPECT_EQ(r.error.includedFrom[0].second, 2);
}

TEST_F(WorldNamesTest, AnIncludeWithoutAFileIsReported) {
  const WorldReadResult r = readWorldNames(write("scene.xml", "<mujoco>\n\n  <include/>\n</mujoco>\n"));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Include);
  EXPECT_EQ(r.error.line, 3);
}

TEST_F(WorldNamesTest, AnIncludeCycleIsReportedNotFollowed) {
  const std::string scene = write("a.xml", "<mujoco><include file=\"b.xml\"/></mujoco>");
  write("b.xml", "<mujoco><include file=\"./a.xml\"/></mujoco>");
  const WorldReadResult r = readWorldNames(scene);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error.kind, WorldReadError::Kind::Unreadable);
  EXPECT_NE(r.error.message.find("includes itself"), std::string::npos) << r.error.message;
  EXPECT_EQ(r.error.includedFrom.size(), 2u);
}

TEST_F(WorldNamesTest, TheRepositoryScenesRead) {
  const fs::path domains = fs::path(CBTL_GOLDEN_DIR) / ".." / ".." / "domains";
  const WorldReadResult feeding = readWorldNames((domains / "feeding" / "feeding.xml").string());
  ASSERT_TRUE(feeding.ok) << feeding.error.file << ":" << feeding.error.line << ": " << feeding.error.message;
  for (const char* body : {"user", "user_head", "table", "wheelchair", "plate", "drink", "utensil", "base_link"})
    EXPECT_TRUE(feeding.names.bodies.count(body)) << body;
  const WorldReadResult home = readWorldNames((domains / "home" / "home.xml").string());
  ASSERT_TRUE(home.ok) << home.error.file << ":" << home.error.line << ": " << home.error.message;
  for (const char* body : {"user", "bed", "table", "shelf", "book_0", "mobile_base"})
    EXPECT_TRUE(home.names.bodies.count(body)) << body;
  for (const char* geom : {"user_forearm_r", "user_head_geom", "table_top", "shelf_layer_0"})
    EXPECT_TRUE(home.names.geoms.count(geom)) << geom;
}

}  // namespace
}  // namespace cbtl
