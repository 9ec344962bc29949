// WorldHost.h — the robot world as the language's built-ins see it: one world::World (a Workspace over the
// domain's shared Scene, FCL shapes, occlusion spec) plus the *reference state*, the world as observed when
// the current CSP was made.
//
// Contract: every built-in starts from the reference state and changes only what its arguments say (the
// arm, the base, a held object, one body's pose); nothing a built-in does is visible to the next one. The
// runtime sets the reference from the domain simulator before it builds a CSP (Planner), so constraints are
// checked against the world the plan will run in; without a simulator it is the scene's initial state
// with the arm at `retract`.
//
// Thread safety: one WorldHost per Program, used by one thread (the Program's contract). Frames: world,
// metres, radians.
#pragma once

#include "robot/world/SurfaceFace.h"
#include "robot/world/WorldOperations.h"  // world::World
#include "runtime/core/Builtins.h"        // rt::BuiltinHost

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace cbtl::bind {

inline constexpr double kSideGraspDepth = 0.03;  // metres from the tool frame to the grasped box centre

class WorldHost final : public rt::BuiltinHost {
 public:
  explicit WorldHost(std::shared_ptr<const world::Scene> scene);

  world::World& world() { return world_; }
  world::Workspace& workspace() { return world_.workspace(); }
  const world::Scene& scene() const { return world_.workspace().scene(); }

  // Replaces the reference state. Returns false (reference unchanged) when the state does not fit the scene.
  bool setReference(const world::WorldState& state);
  const world::WorldState& reference() const { return reference_; }

  // Puts the workspace at the reference state with `base` and arm `q` (and, when `held` names an object, that
  // object attached at nominalGrasp(held) instead of the reference's grasp). false when q is out of limits
  // or `held` is not a movable object.
  bool pose(const world::Pose2& base, const world::ArmConfig& q, const std::string* held = nullptr);
  // Moves one movable object for a query; the next pose() call puts it back.
  bool moveObject(const std::string& object, const world::Pose3& pose);

  // The grasp of `object`: the reference's when the robot holds it; else the scene's standard grasp, the site
  // "<object>_tool" whose frame is the tool frame at that grasp (home.xml's duster_tool); else the side grasp
  // sideGrasp(object, -pi/2). The object's frame in the tool frame.
  std::optional<world::Pose3> nominalGrasp(const std::string& object);
  // Tool pose grasping the box of `object` (at `objectPose`) from the side: with yaw = -pi/2 the tool z (the
  // approach) runs along the object's +y, tool x along its x (the fingers close across it) and tool y along
  // its -z; other yaws turn that about the object's z by yaw + pi/2. The box centre lies kSideGraspDepth
  // ahead of the tool frame (between the finger tips). With yaw = -pi/2 this is the carry grasp of the home
  // scene's books (robot/actions/StandardGrasps.h bookToolInBody).
  std::optional<world::Pose3> sideGrasp(const std::string& object, const world::Pose3& objectPose, double yaw);

  // A named arm configuration (world/NamedConfigurations.h: the scene's conf_<name>, else the standard table).
  std::optional<world::ArmConfig> namedConf(const std::string& name) const;
  std::optional<world::SurfaceFace> surfaceTop(const std::string& geom) const;
  // The box geom whose top face the object at its reference pose rests on (bottom within 1 cm, centre over
  // the face); empty when none.
  std::string supportSurface(const std::string& object);
  // The object's lowest point and footprint (world AABB half-extents in x, y) at `pose`.
  struct Footprint {
    double bottom = 0, centerX = 0, centerY = 0, halfX = 0, halfY = 0;
  };
  std::optional<Footprint> footprint(const std::string& object, const world::Pose3& pose) const;

  int planIterations = 3000;  // budgets of the feasibility built-ins (WorldBuiltins.h)
  int ikAttempts = 10;

 private:
  world::World world_;
  world::WorldState reference_;
  bool dirty_ = true;  // the workspace's objects or grasp differ from the reference
};

}  // namespace cbtl::bind
