// JSON world states for `cbtl render --state`.
#include "robot/world/StateJson.h"
#include "tests/unit/world/WorldTestSupport.h"

namespace cbtl::world {
namespace {

TEST(WorldStateJson, AppliesArmBaseObjectsAndHeld) {
  Workspace ws(test::homeScene());
  const auto r = applyStateJson(ws, R"({
    "arm": "retract", "base": {"x": 0.5, "y": -0.2, "yaw": 0.3}, "gripper": 0.5,
    "objects": {"book_0": {"position": [0.1, 0.2, 0.3], "yaw": 1.0}}, "held": "book_0"})");
  ASSERT_EQ(r.status, StateJsonStatus::Ok) << r.message;
  EXPECT_EQ(ws.state().arm, configs::kRetract);
  EXPECT_NEAR(ws.state().base.y, -0.2, 1e-12);
  EXPECT_EQ(ws.heldObject(), ws.scene().objectIndex("book_0"));
  EXPECT_NEAR((ws.objectPose("book_0")->position - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 0.0, 1e-9);
}

TEST(WorldStateJson, ErrorsNameTheProblem) {
  Workspace ws(test::feedingScene());
  const ArmConfig before = ws.state().arm;
  auto r = applyStateJson(ws, "{\"arm\": [1, 2]", "s.json");
  EXPECT_EQ(r.status, StateJsonStatus::BadJson);
  EXPECT_NE(r.message.find("s.json"), std::string::npos);
  r = applyStateJson(ws, R"({"arm": [0, 0, 0]})");
  EXPECT_EQ(r.status, StateJsonStatus::BadValue);
  r = applyStateJson(ws, R"({"objects": {"teapot": {"position": [0, 0, 0]}}})");
  EXPECT_EQ(r.status, StateJsonStatus::BadValue);
  EXPECT_NE(r.message.find("teapot"), std::string::npos);
  r = applyStateJson(ws, R"({"arms": "home"})");
  EXPECT_NE(r.message.find("arms"), std::string::npos);
  r = applyStateJson(ws, R"({"arm": [0, 3.0, 0, 0, 0, 0, 0]})");
  EXPECT_EQ(r.status, StateJsonStatus::BadValue);
  EXPECT_EQ(ws.state().arm, before);
  EXPECT_EQ(applyStateFile(ws, "/nonexistent/state.json").status, StateJsonStatus::FileNotFound);
}

TEST(WorldStateJson, SetsFixturesAndNamesAnUnknownOne) {
  Workspace ws(test::feedingScene());
  auto r = applyStateJson(ws, R"({"fixtures": {"table_round": {"position": [0.3505, 0.4495, 0]}}})");
  ASSERT_EQ(r.status, StateJsonStatus::Ok) << r.message;
  EXPECT_NEAR(ws.state().fixtures.at("table_round").position.z(), 0.0, 1e-12);
  r = applyStateJson(ws, R"({"fixtures": {"plate": {"position": [0, 0, 0]}}})");
  EXPECT_EQ(r.status, StateJsonStatus::BadValue);
  EXPECT_NE(r.message.find("plate"), std::string::npos);
}

}  // namespace
}  // namespace cbtl::world
