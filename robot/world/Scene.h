// Scene.h — a loaded MuJoCo robot scene: the compiled model plus the names the world API looks up.
//
// A Scene is immutable after loading (but for its motion cache, see motionCache()) and shared (std::shared_ptr<const
// Scene>) by every thread; each thread owns its own Workspace (mjData) over it. A robot scene must contain the Gen3 arm
// of domains/assets/gen3.xml (joints joint_1..joint_7, site tool_frame, bodies base_link and end_effector_link).
// Optional parts: a mobile base (body mobile_base with joints base_x, base_y, base_yaw), finger slide
// joints finger_left / finger_right, movable objects (bodies whose first joint is a free joint), and fixtures:
// scenery a scenario puts in place (MuJoCo mocap bodies: the feeding scene's two tables), which never move during a
// plan but whose poses are part of the WorldState; their geoms count as scenery everywhere.
// Units: metres, radians.
#pragma once

#include "robot/world/Pose.h"
#include "robot/world/SubtreeKinematics.h"

#include <mujoco/mujoco.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cbtl::world {

enum class LoadStatus {
  Ok,
  FileNotFound,    // the path does not name a readable file
  ParseError,      // MuJoCo rejected the XML (message has MuJoCo's text with line numbers)
  NotARobotScene,  // the model compiled but lacks the Gen3 arm names listed above
  BadClearance,    // a clearance names a body the scene does not have, or a distance that is not >= 0
};

// A class of the scene's bodies and the distance the robot, and what it holds, keeps from each of them (a program's
// `clearance person: "user" >= 5 cm;`). Every collision check of the Scene's pairs requires it.
struct BodyClearance {
  std::string name;                 // "person"
  std::vector<std::string> bodies;  // body names; each covers the bodies below it in the scene tree
  double distance = 0;              // metres, >= 0
  std::string declaredAt;           // "file:line:col" of the declaration, for messages; may be empty
};

class Scene;
class MotionCache;
class GeomDistance;
class MotionBound;

struct SceneLoadResult {
  LoadStatus status = LoadStatus::ParseError;
  std::string message;                 // empty when status == Ok; always names the file otherwise
  std::shared_ptr<const Scene> scene;  // non-null iff status == Ok
};

// What a body is, for collision classification.
enum class BodyKind : unsigned char {
  Scenery,  // the world body and everything welded to it or to non-robot, non-object bodies
  Robot,    // arm links, the mobile base and its stand
  Gripper,  // end_effector_link and the fingers (also robot; a held object may touch these)
  Object,   // a movable object (a body with a free joint) or a child of one
};

struct ObjectInfo {
  std::string name;  // the body name
  int body = -1;     // MuJoCo body id
  int qposAdr = -1;  // first of the free joint's 7 qpos entries (x y z qw qx qy qz)
};

struct FixtureInfo {
  std::string name;  // the body name
  int body = -1;     // MuJoCo body id
  int mocapId = -1;  // index into mjData's mocap_pos / mocap_quat
};

class Scene {
 public:
  // Loads an MJCF file; includes resolve relative to the file's directory. `clearances` become part of every
  // candidate pair's keep-out (below).
  static SceneLoadResult loadFile(const std::string& path, const std::vector<BodyClearance>& clearances = {});

  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  const mjModel* model() const { return model_; }

  // Arm joints (index 0..6 for joint_1..joint_7).
  int armQposAdr(int i) const { return armQpos_[i]; }
  int armDofAdr(int i) const { return armDof_[i]; }
  bool armContinuous(int i) const { return continuous_[i]; }
  double armLower(int i) const { return lower_[i]; }  // -pi for continuous joints
  double armUpper(int i) const { return upper_[i]; }  //  pi for continuous joints
  // True when every limited joint of q lies within its range (continuous joints are always fine).
  bool withinLimits(const ArmConfig& q) const;
  // Wraps continuous joints to [-pi, pi) and clamps limited joints into range.
  ArmConfig normalize(const ArmConfig& q) const;

  bool hasMobileBase() const { return baseQpos_[0] >= 0; }
  int baseQposAdr(int i) const { return baseQpos_[i]; }      // x, y, yaw; -1 without a mobile base
  int fingerQposAdr(int i) const { return fingerQpos_[i]; }  // left, right; -1 if absent
  double fingerTravel() const { return fingerTravel_; }      // metres from open to closed

  int toolSite() const { return toolSite_; }
  int siteId(std::string_view name) const;  // -1 if absent
  int bodyId(std::string_view name) const;  // -1 if absent
  int geomId(std::string_view name) const;  // -1 if absent
  std::string bodyName(int body) const;
  std::string geomName(int geom) const;

  BodyKind bodyKind(int body) const { return kinds_[static_cast<size_t>(body)]; }
  // Index into objects() of the movable object that owns `body`, or -1.
  int objectOfBody(int body) const { return objectOfBody_[static_cast<size_t>(body)]; }
  const std::vector<ObjectInfo>& objects() const { return objects_; }
  int objectIndex(std::string_view name) const;  // -1 if absent
  // Mocap bodies, in body order.
  const std::vector<FixtureInfo>& fixtures() const { return fixtures_; }
  int fixtureIndex(std::string_view name) const;  // -1 if absent

  // Candidate geom pairs for the robot's collision checks, ordered so that geom_type[g1] <= geom_type[g2]: the
  // pairs MuJoCo's own filters let through (contype/conaffinity, same weld body, parent-child, <exclude>), with the
  // larger of the two geoms' margins, and the explicit <contact><pair> elements, with the pair's margin. As in
  // MuJoCo 2.2.2, an explicit pair replaces the filtered pair of the same two geoms (and only that one).
  // A pair's margin is at least the clearance of the body the robot (or the held object) meets: robot × world pairs
  // take the world geom's clearance, object pairs (used when that object is held) the other geom's.
  struct GeomPair {
    int g1, g2;
    double margin;  // metres: closer than this counts as penetrating by the difference
  };
  // Geoms of robot bodies (BodyKind Robot or Gripper), in id order.
  const std::vector<int>& robotGeoms() const { return robotGeoms_; }
  const std::vector<GeomPair>& selfPairs() const { return selfPairs_; }    // robot × robot
  const std::vector<GeomPair>& robotPairs() const { return robotPairs_; }  // robot × scenery/object
  // Geoms of object `index` × scenery and other objects' geoms (used when that object is held).
  const std::vector<GeomPair>& objectPairs(int index) const { return objectPairs_[static_cast<size_t>(index)]; }
  // The keep-out distance the collision checks apply between geoms g1 and g2 (metres): the explicit pair's margin,
  // else the larger geom margin when MuJoCo's filters let the pair collide, else 0 (the pair is never checked); and at
  // least the clearance of each of the two that is not a robot geom.
  double keepOut(int g1, int g2) const;

  // The clearances the scene was loaded with, and the one that applies to body `b` (the largest distance among
  // the classes it belongs to), or null.
  const std::vector<BodyClearance>& clearances() const { return clearances_; }
  const BodyClearance* clearanceOfBody(int b) const {
    const int c = clearanceOf_[static_cast<size_t>(b)];
    return c < 0 ? nullptr : &clearances_[static_cast<size_t>(c)];
  }
  double clearanceDistance(int body) const {
    const BodyClearance* c = clearanceOfBody(body);
    return c ? c->distance : 0.0;
  }
  // The largest margin any candidate pair of geom g uses (its own, or an explicit pair's), for the broad phase.
  double reachMargin(int g) const { return reachMargin_[static_cast<size_t>(g)]; }

  // The bodies whose poses depend on the arm joints (rooted at joint_1's body), on the base joints (rooted at
  // the mobile base; empty without one), and on movable object `index`'s free joint: the Workspace recomputes
  // only these when only those joints change (SubtreeKinematics.h).
  const KinematicSubtree& armSubtree() const { return armSubtree_; }
  const KinematicSubtree& baseSubtree() const { return baseSubtree_; }
  const KinematicSubtree& objectSubtree(int index) const { return objectSubtrees_[static_cast<size_t>(index)]; }
  // The MuJoCo joint id of arm joint i (0..6).
  int armJointId(int i) const { return armJoint_[i]; }

  // The motion-planning answers of every Workspace over this scene (MotionQuery.h). The one mutable part of a
  // Scene: shared, locked, and transparent (a cached answer equals a fresh one).
  MotionCache& motionCache() const { return *motionCache_; }

  // Exact distances between the scene's geoms (GeomDistance.h) and the speed bounds of the robot's joints
  // (MotionBound.h): what the collision checks and certified segments measure with.
  const GeomDistance& geomDistance() const { return *geomDistance_; }
  const MotionBound& motionBound() const { return *motionBound_; }
  // The body whose frame the held object follows (end_effector_link).
  int endEffectorBody() const { return endEffector_; }
  // A number no other Scene of this process has (per-thread caches key on it; addresses can be reused).
  std::uint64_t serial() const { return serial_; }

 private:
  void buildPairs();
  std::string applyClearances(const std::vector<BodyClearance>& clearances);  // error message, empty on success
  bool mujocoWouldCollide(int g1, int g2) const;

  explicit Scene(mjModel* m);
  std::string initialise();  // returns an error message, empty on success

  mjModel* model_ = nullptr;
  std::array<int, kArmDof> armQpos_{}, armDof_{}, armJoint_{};
  std::array<bool, kArmDof> continuous_{};
  std::array<double, kArmDof> lower_{}, upper_{};
  std::array<int, 3> baseQpos_{-1, -1, -1};
  std::array<int, 2> fingerQpos_{-1, -1};
  double fingerTravel_ = 0.0;
  int toolSite_ = -1;
  std::vector<BodyKind> kinds_;
  std::vector<int> objectOfBody_;
  std::vector<ObjectInfo> objects_;
  std::vector<FixtureInfo> fixtures_;
  std::vector<int> robotGeoms_;
  std::vector<GeomPair> selfPairs_, robotPairs_;
  std::vector<double> reachMargin_;
  std::map<std::pair<int, int>, double> explicitMargin_;  // the <pair> margins, keyed by (lower, higher) geom id
  std::vector<std::vector<GeomPair>> objectPairs_;
  std::vector<BodyClearance> clearances_;
  std::vector<int> clearanceOf_;  // per body: index into clearances_, or -1
  KinematicSubtree armSubtree_, baseSubtree_;
  std::vector<KinematicSubtree> objectSubtrees_;
  std::unique_ptr<MotionCache> motionCache_;
  std::unique_ptr<const GeomDistance> geomDistance_;
  std::unique_ptr<const MotionBound> motionBound_;
  int endEffector_ = -1;
  std::uint64_t serial_ = 0;
};

}  // namespace cbtl::world
