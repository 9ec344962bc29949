#include "robot/world/GraspClosure.h"

#include "robot/world/Separation.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace cbtl::world {
namespace {

constexpr double kTouch = 1e-5;    // metres: a finger this near the object touches it (advancement stops)
constexpr int kMaxAdvances = 200;  // conservative advancement converges long before this on the scenes' shapes

// One finger of the gripper: its geoms, and the world direction its slide joint closes along.
struct Finger {
  const char* name = "";
  std::vector<int> geoms;
  Eigen::Vector3d closing = Eigen::Vector3d::Zero();  // unit, world frame
  double atRest = 0;                                  // the joint's travel in the Workspace's current state
};

bool collidable(const mjModel* m, int g) { return (m->geom_contype[g] | m->geom_conaffinity[g]) != 0; }

std::vector<int> objectGeoms(const Workspace& ws, int object) {
  const mjModel* m = ws.model();
  std::vector<int> out;
  for (int g = 0; g < m->ngeom; ++g)
    if (collidable(m, g) && ws.scene().objectOfBody(m->geom_bodyid[g]) == object) out.push_back(g);
  return out;
}

// The two fingers, or an empty array member when the scene lacks one.
std::array<Finger, 2> fingers(const Workspace& ws, bool& ok) {
  static constexpr const char* kJoints[2] = {"finger_left", "finger_right"};
  static constexpr const char* kNames[2] = {"left", "right"};
  const mjModel* m = ws.model();
  const mjData* d = ws.data();
  std::array<Finger, 2> out;
  ok = true;
  for (int i = 0; i < 2; ++i) {
    const int j = mj_name2id(m, mjOBJ_JOINT, kJoints[i]);
    if (j < 0 || m->jnt_type[j] != mjJNT_SLIDE) {
      ok = false;
      continue;
    }
    const int body = m->jnt_bodyid[j];
    Finger& f = out[static_cast<size_t>(i)];
    f.name = kNames[i];
    const double* r = d->xmat + 9 * body;  // row-major: world = r * local
    const double* a = m->jnt_axis + 3 * j;
    f.closing = Eigen::Vector3d(r[0] * a[0] + r[1] * a[1] + r[2] * a[2], r[3] * a[0] + r[4] * a[1] + r[5] * a[2],
                                r[6] * a[0] + r[7] * a[1] + r[8] * a[2])
                    .normalized();
    f.atRest = d->qpos[m->jnt_qposadr[j]];
    for (int g = 0; g < m->ngeom; ++g)
      if (m->geom_bodyid[g] == body && collidable(m, g)) f.geoms.push_back(g);
    if (f.geoms.empty()) ok = false;
  }
  return out;
}

// Moves the finger's geoms (only their world positions: nothing else reads them here) to travel `t`.
void placeFinger(mjData* d, const Finger& f, const std::vector<Eigen::Vector3d>& home, double t) {
  for (std::size_t k = 0; k < f.geoms.size(); ++k) {
    const Eigen::Vector3d p = home[k] + (t - f.atRest) * f.closing;
    for (int c = 0; c < 3; ++c) d->geom_xpos[3 * f.geoms[k] + c] = p[c];
  }
}

struct Nearest {
  double separation = std::numeric_limits<double>::infinity();
  int fingerGeom = -1, objectGeom = -1;
};

Nearest nearest(const Workspace& ws, const std::vector<int>& mine, const std::vector<int>& theirs) {
  Nearest n;
  for (int a : mine)
    for (int b : theirs) {
      const double s = exactSeparation(ws, a, b);
      if (s < n.separation) n = {s, a, b};
    }
  return n;
}

// The travel at which the finger first touches the object, searching up to `limit` (beyond the real travel, so a
// push can be measured); the last measured separation when it never does.
struct FirstTouch {
  bool touches = false;
  double travel = 0;
  Nearest at;  // the nearest pair where the search stopped
};

FirstTouch firstTouch(Workspace& ws, const Finger& f, const std::vector<int>& object, double limit) {
  mjData* d = ws.data();
  std::vector<Eigen::Vector3d> home;
  for (int g : f.geoms) home.emplace_back(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
  FirstTouch out;
  double t = 0;
  for (int k = 0; k < kMaxAdvances; ++k) {
    placeFinger(d, f, home, t);
    out.at = nearest(ws, f.geoms, object);
    if (out.at.separation <= kTouch) {
      out.touches = true;
      break;
    }
    if (t >= limit) break;
    t = std::min(limit, t + out.at.separation);  // the finger cannot come nearer than it moves
  }
  out.travel = t;
  placeFinger(d, f, home, f.atRest);
  return out;
}

}  // namespace

const char* toString(GraspStatus s) {
  switch (s) {
    case GraspStatus::Holds:
      return "holds";
    case GraspStatus::ClosesOnAir:
      return "closes on air";
    case GraspStatus::Blocked:
      return "blocked";
    case GraspStatus::NoGripper:
      return "no gripper";
  }
  return "?";
}

GripperContact gripperContact(const Workspace& ws, int object) {
  const mjModel* m = ws.model();
  std::vector<int> gripper;
  for (int g = 0; g < m->ngeom; ++g)
    if (collidable(m, g) && ws.scene().bodyKind(m->geom_bodyid[g]) == BodyKind::Gripper) gripper.push_back(g);
  const Nearest n = nearest(ws, gripper, objectGeoms(ws, object));
  return {n.separation, n.fingerGeom, n.objectGeom};
}

GraspClosure closeOn(Workspace& ws, int object) {
  GraspClosure out;
  const Scene& scene = ws.scene();
  const double travel = scene.fingerTravel();
  if (object < 0 || object >= static_cast<int>(scene.objects().size())) {
    out.detail = "no such object";
    return out;
  }
  const std::string& name = scene.objects()[static_cast<size_t>(object)].name;
  const WorldState before = ws.state();
  WorldState open = before;
  open.gripper = 1.0;
  ws.setState(open);

  bool ok = false;
  const std::array<Finger, 2> f = fingers(ws, ok);
  if (!ok || travel <= 0) {
    ws.setState(before);
    out.detail = "the scene has no two-finger gripper (slide joints finger_left and finger_right)";
    return out;
  }
  const std::vector<int> geoms = objectGeoms(ws, object);
  if (geoms.empty()) {
    ws.setState(before);
    out.status = GraspStatus::ClosesOnAir;
    out.detail = fmt::format("{} has no solid geom the fingers could touch", name);
    return out;
  }
  const double openGap = exactSeparation(ws, f[0].geoms.front(), f[1].geoms.front());
  const GripperContact open0 = gripperContact(ws, object);
  if (open0.separation < -kGraspCompliance) {
    out.status = GraspStatus::Blocked;
    out.detail = fmt::format("the open gripper's {} is {:.1f} mm inside {}", scene.geomName(open0.gripperGeom),
                             -1000 * open0.separation, scene.geomName(open0.objectGeom));
    ws.setState(before);
    return out;
  }
  // Each finger alone, as far as the other finger's whole travel could push the object towards it.
  std::array<FirstTouch, 2> touch;
  for (int i = 0; i < 2; ++i)
    touch[static_cast<size_t>(i)] = firstTouch(ws, f[static_cast<size_t>(i)], geoms, 2 * travel);
  ws.setState(before);

  for (int i = 0; i < 2; ++i) {
    const FirstTouch& t = touch[static_cast<size_t>(i)];
    if (!t.touches) {
      out.status = GraspStatus::ClosesOnAir;
      out.detail = fmt::format("the {} finger closes on air: at the end of its travel it is still {:.1f} mm from {}",
                               f[static_cast<size_t>(i)].name, 1000 * t.at.separation, scene.geomName(t.at.objectGeom));
      return out;
    }
  }
  // Closing together, the first finger to touch pushes the object until the other touches: both stop at the mean.
  const double meet = 0.5 * (touch[0].travel + touch[1].travel);
  const double push = 0.5 * (touch[1].travel - touch[0].travel);  // > 0: the left finger touched first
  const double closed = meet + kGraspSqueeze;
  if (closed > travel) {
    out.status = GraspStatus::ClosesOnAir;
    out.detail = fmt::format("the fingers close on air: {} is {:.1f} mm narrower than the gripper closes", name,
                             1000 * (closed - travel));
    return out;
  }
  if (std::abs(push) > kGraspMaxPush) {
    out.status = GraspStatus::ClosesOnAir;
    out.detail = fmt::format(
        "{} is {:.1f} mm off the gripper's centre: the {} finger would push it that far before "
        "the other touched (at most {:.0f} mm)",
        name, 1000 * std::abs(push), push > 0 ? "left" : "right", 1000 * kGraspMaxPush);
    return out;
  }
  out.status = GraspStatus::Holds;
  out.gripper = 1.0 - closed / travel;
  out.push = push;
  // The left finger closes along f[0].closing; pushed by it, the object moves that way.
  out.pushWorld = push * f[0].closing;
  out.width = openGap - 2 * closed;
  return out;
}

GraspClosure gripHeld(Workspace& ws) {
  if (ws.heldObject() < 0 || !ws.state().held) {
    GraspClosure none;
    none.detail = "nothing is held";
    return none;
  }
  const WorldState before = ws.state();
  const std::string object = before.held->object;
  const int index = ws.heldObject();
  ws.setHeld(std::nullopt);  // the object stays where the grasp put it
  const GraspClosure closure = closeOn(ws, index);
  if (!closure.holds()) {
    ws.setState(before);
    return closure;
  }
  WorldState gripped = ws.state();
  gripped.gripper = closure.gripper;
  gripped.objects[object].position += closure.pushWorld;
  ws.setState(gripped);
  ws.setHeld(object);
  return closure;
}

}  // namespace cbtl::world
