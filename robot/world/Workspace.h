// Workspace.h — one thread's mutable view of a Scene: an mjData, the current WorldState and forward
// kinematics.
//
// Thread safety: a Workspace is used by one thread at a time; create one per thread over the same shared
// Scene. Every query below reflects the state last set with setState()/setArm()/setBase(); kinematics are
// recomputed eagerly by the setters, so queries are cheap.
// Frames: world coordinates, metres, unit quaternions.
#pragma once

#include "robot/world/Scene.h"
#include "robot/world/WorldState.h"

#include <memory>
#include <optional>
#include <string_view>

namespace cbtl::world {

enum class StateStatus {
  Ok,
  UnknownObject,  // an object (fixture) name in the state is not a movable object (fixture) of the scene
  OutOfLimits,    // an arm joint lies outside its range, or a value is not finite
};

const char* toString(StateStatus s);

class Workspace {
 public:
  explicit Workspace(std::shared_ptr<const Scene> scene);
  ~Workspace();
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;

  const Scene& scene() const { return *scene_; }
  const mjModel* model() const { return scene_->model(); }
  mjData* data() { return data_; }
  const mjData* data() const { return data_; }

  // Replaces the whole state. On failure nothing changes.
  StateStatus setState(const WorldState& state);
  const WorldState& state() const { return state_; }

  // Fast paths used by IK and planners: change one part of the state and recompute kinematics. Continuous
  // joints are stored as given (not wrapped); limits are not checked here.
  void setArm(const ArmConfig& q);
  void setBase(const Pose2& base);
  // Attaches an object at its current pose relative to the tool, or detaches (nullopt).
  StateStatus setHeld(const std::optional<std::string>& object);
  // Moves a movable object (ignored for the held object, which follows the tool).
  StateStatus setObjectPose(std::string_view object, const Pose3& pose);

  // Puts a fixture (Scene.h) at `pose`: the scenario's set-up, never an action's effect.
  StateStatus setFixturePose(std::string_view fixture, const Pose3& pose);

  // Forward kinematics at the current state.
  Pose3 sitePose(int site) const;
  std::optional<Pose3> sitePose(std::string_view site) const;
  Pose3 toolPose() const { return sitePose(scene_->toolSite()); }
  Pose3 bodyPose(int body) const;
  std::optional<Pose3> objectPose(std::string_view object) const;
  // Tool pose for an arm configuration (the state is left at q).
  Pose3 forwardKinematics(const ArmConfig& q);

  // Index of the held object in scene().objects(), or -1.
  int heldObject() const { return heldIndex_; }

 private:
  void writeObject(int index, const Pose3& pose);
  void writeFixture(int index, const Pose3& pose);
  // Recomputes the kinematics after a change of the joints of `moved` (the default, an empty subtree, means
  // anything may have changed: a full mj_kinematics pass), then the held object's pose from the tool's.
  void recompute(const KinematicSubtree& moved = KinematicSubtree());

  std::shared_ptr<const Scene> scene_;
  mjData* data_ = nullptr;
  WorldState state_;
  int heldIndex_ = -1;
};

}  // namespace cbtl::world
