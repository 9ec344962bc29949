// Scene loading: good scenes load, bad or missing files give a clear error instead of a crash.
#include "robot/world/MujocoErrors.h"
#include "robot/world/NamedConfigurations.h"
#include "robot/world/WorldState.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <filesystem>
#include <fstream>

namespace cbtl::world {
namespace {

// Loads `xml` written to the temporary file `name` (removed again).
SceneLoadResult loadText(const std::string& xml, const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << xml;
  SceneLoadResult r = Scene::loadFile(path.string());
  std::filesystem::remove(path);
  return r;
}

using test::domainsPath;

TEST(WorldScene, FeedingSceneHasTheExpectedParts) {
  auto r = Scene::loadFile(domainsPath("feeding/feeding.xml"));
  ASSERT_EQ(r.status, LoadStatus::Ok) << r.message;
  const Scene& s = *r.scene;
  EXPECT_FALSE(s.hasMobileBase());
  EXPECT_GE(s.objectIndex("plate"), 0);
  EXPECT_GE(s.objectIndex("drink"), 0);
  EXPECT_GE(s.objectIndex("utensil"), 0);
  EXPECT_GE(s.siteId("user_eyes"), 0);
  for (int i : {0, 2, 4, 6}) EXPECT_TRUE(s.armContinuous(i)) << i;
  EXPECT_NEAR(s.armLower(1), -2.41, 1e-9);
  EXPECT_NEAR(s.armUpper(3), 2.66, 1e-9);
  EXPECT_NEAR(s.armUpper(5), 2.23, 1e-9);
  EXPECT_EQ(s.bodyKind(s.bodyId("shoulder_link")), BodyKind::Robot);
  EXPECT_EQ(s.bodyKind(s.bodyId("left_finger")), BodyKind::Gripper);
  EXPECT_EQ(s.bodyKind(s.bodyId("table")), BodyKind::Scenery);
}

TEST(WorldScene, HomeSceneHasMobileBaseShelfAndBooks) {
  auto r = Scene::loadFile(domainsPath("home/home.xml"));
  ASSERT_EQ(r.status, LoadStatus::Ok) << r.message;
  EXPECT_TRUE(r.scene->hasMobileBase());
  for (int i = 0; i < 9; ++i) EXPECT_GE(r.scene->objectIndex("book_" + std::to_string(i)), 0);
  EXPECT_GE(r.scene->objectIndex("duster"), 0);
  for (const char* g : {"shelf_layer_0", "shelf_layer_1", "shelf_layer_2", "table_top", "side_table_2_top"})
    EXPECT_GE(r.scene->geomId(g), 0) << g;
}

TEST(WorldScene, MissingFileIsReported) {
  auto r = Scene::loadFile("/nonexistent/dir/scene.xml");
  EXPECT_EQ(r.status, LoadStatus::FileNotFound);
  EXPECT_EQ(r.scene, nullptr);
  EXPECT_NE(r.message.find("/nonexistent/dir/scene.xml"), std::string::npos) << r.message;
}

TEST(WorldScene, CorruptFileIsAnErrorNotACrash) {
  const auto path = std::filesystem::temp_directory_path() / "cbtl_world_corrupt_scene.xml";
  {
    std::ofstream out(path);
    out << "<mujoco><worldbody><body name=\"a\"><geom type=\"box\" size=\"0.1 0.1\"</body></worldbody>";
  }
  auto r = Scene::loadFile(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(r.status, LoadStatus::ParseError);
  EXPECT_EQ(r.scene, nullptr);
  EXPECT_NE(r.message.find("cbtl_world_corrupt_scene.xml"), std::string::npos) << r.message;
}

TEST(WorldScene, ModelWithoutArmIsRejected) {
  const auto r =
      loadText("<mujoco><worldbody><geom type=\"sphere\" size=\"0.1\"/></worldbody></mujoco>", "cbtl_world_ball.xml");
  EXPECT_EQ(r.status, LoadStatus::NotARobotScene);
  EXPECT_NE(r.message.find("cbtl_world_ball.xml"), std::string::npos);
}

TEST(WorldScene, MujocoErrorsThrowInsteadOfExiting) {
  installMujocoHandlers();
  EXPECT_THROW(mju_error("deliberate test error"), MujocoError);
  EXPECT_NO_THROW(mju_warning("deliberate test warning"));
}

TEST(WorldScene, InvalidAttributeIsAParseError) {
  const auto r = loadText("<mujoco><worldbody><geom type=\"nonsense\"/></worldbody></mujoco>", "cbtl_world_bad.xml");
  EXPECT_EQ(r.status, LoadStatus::ParseError);
  EXPECT_FALSE(r.message.empty());
}

}  // namespace
}  // namespace cbtl::world

namespace cbtl::world {

TEST(NamedConfigurations, TheSceneNamesComeFirstThenTheStandardTable) {
  const auto feeding = test::feedingScene();
  const auto before = namedConfiguration(*feeding, "beforeTransfer");
  ASSERT_TRUE(before.has_value());
  EXPECT_NEAR((*before)[0], -2.60005, 1e-9);  // feeding.xml's conf_beforeTransfer
  EXPECT_EQ(namedConfiguration(*feeding, "retract"), configs::kRetract);
  EXPECT_FALSE(namedConfiguration(*feeding, "noSuchPose").has_value());
  EXPECT_FALSE(namedConfiguration(*test::homeScene(), "beforeTransfer").has_value());   // Feeding's only
  EXPECT_TRUE(namedConfiguration(*test::homeScene(), "homeSceneInitial").has_value());  // home.xml's
  EXPECT_FALSE(namedConfiguration(*feeding, "homeSceneInitial").has_value());
}

TEST(NamedConfigurations, NamesListTheSceneAndTheStandardTable) {
  const std::vector<std::string> feeding = namedConfigurationNames(*test::feedingScene());
  const std::vector<std::string> expected{"abovePlate", "beforeTransfer",    "drinkGaze", "home",
                                          "retract",    "utensilAboveMount", "zero"};
  EXPECT_EQ(feeding, expected);
  const std::vector<std::string> home = namedConfigurationNames(*test::homeScene());
  EXPECT_EQ(home, (std::vector<std::string>{"home", "homeSceneInitial", "retract", "zero"}));
}

}  // namespace cbtl::world
