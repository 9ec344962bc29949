#include "robot/actions/ClearanceExceptions.h"

#include <fmt/core.h>

#include <cmath>

namespace cbtl::actions {

namespace {

bool partOf(const std::string& text, world::ContactAllowance::Part& part) {
  using Part = world::ContactAllowance::Part;
  for (const Part p : {Part::HeldObject, Part::Gripper, Part::Robot}) {
    if (text == world::toString(p)) {
      part = p;
      return true;
    }
  }
  return false;
}

std::string declared(const sim::ClearanceException& e) {
  return e.declaredAt.empty() ? "allow" : fmt::format("allow at {}", e.declaredAt);
}

}  // namespace

bool resolveClearanceExceptions(const world::Scene& scene, const std::vector<sim::ClearanceException>& exceptions,
                                std::vector<world::ContactAllowance>& out, std::string& error) {
  const mjModel* m = scene.model();
  for (const sim::ClearanceException& e : exceptions) {
    world::ContactAllowance a;
    if (!partOf(e.part, a.part)) {
      error = fmt::format("{}: '{}' is not a part of the robot (robot, gripper or held)", declared(e), e.part);
      return false;
    }
    if (!std::isfinite(e.separation)) {
      error = fmt::format("{}: the distance is not a finite number", declared(e));
      return false;
    }
    a.separation = e.separation;
    for (const std::string& name : e.names) {
      if (const int root = scene.bodyId(name); root >= 0) {
        // Parents precede children in MuJoCo's body order: one pass finds the subtree.
        std::vector<char> below(static_cast<std::size_t>(m->nbody), 0);
        below[static_cast<std::size_t>(root)] = 1;
        for (int b = root; b < m->nbody; ++b) {
          if (b != root && !below[static_cast<std::size_t>(m->body_parentid[b])]) continue;
          below[static_cast<std::size_t>(b)] = 1;
          a.geom = -1;
          a.body = b;
          out.push_back(a);
        }
      } else if (const int geom = scene.geomId(name); geom >= 0) {
        a.geom = geom;
        a.body = -1;
        out.push_back(a);
      } else {
        error = fmt::format("{}: the scene has no body or geom '{}'", declared(e), name);
        return false;
      }
    }
  }
  return true;
}

}  // namespace cbtl::actions
