#include "robot/actions/CallArguments.h"

#include <cmath>

namespace cbtl::actions {

const char* kindName(sim::Value::Kind kind) {
  switch (kind) {
    case sim::Value::Kind::Number:
      return "a number";
    case sim::Value::Kind::Vector:
      return "a vector";
    case sim::Value::Kind::Name:
      return "a name";
    case sim::Value::Kind::Names:
      return "a set of names";
  }
  return "a value";
}

std::string checkArguments(const sim::ActionCall& call, std::initializer_list<ArgShape> shapes) {
  if (call.args.size() != shapes.size()) {
    return call.name + " takes " + std::to_string(shapes.size()) + " argument(s), got " +
           std::to_string(call.args.size());
  }
  std::size_t i = 0;
  for (const ArgShape& shape : shapes) {
    const sim::Value& v = call.args[i];
    const std::string which = call.name + ": argument " + std::to_string(i + 1);
    if (v.kind != shape.kind) return which + " must be " + kindName(shape.kind) + ", got " + kindName(v.kind);
    if (shape.kind == sim::Value::Kind::Vector && shape.length != 0 && v.vector.size() != shape.length) {
      return which + " must have " + std::to_string(shape.length) + " components, got " +
             std::to_string(v.vector.size());
    }
    ++i;
  }
  return {};
}

namespace {
bool allFinite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}
}  // namespace

std::optional<world::Pose3> decodePose3(const std::vector<double>& v) {
  if (v.size() != 7 || !allFinite(v)) return std::nullopt;
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // Eigen's constructor order is (w, x, y, z)
  if (q.norm() < 1e-9) return std::nullopt;
  return world::Pose3{Eigen::Vector3d(v[0], v[1], v[2]), q.normalized()};
}

std::optional<world::Pose2> decodePose2(const std::vector<double>& v) {
  if (v.size() != 3 || !allFinite(v)) return std::nullopt;
  return world::Pose2{v[0], v[1], v[2]};
}

std::optional<world::ArmConfig> decodeConf(const std::vector<double>& v) {
  if (v.size() != world::kArmDof || !allFinite(v)) return std::nullopt;
  world::ArmConfig q{};
  for (int i = 0; i < world::kArmDof; ++i) q[static_cast<std::size_t>(i)] = v[static_cast<std::size_t>(i)];
  return q;
}

std::vector<double> encodePose3(const world::Pose3& p) {
  const Eigen::Quaterniond q = p.orientation.normalized();
  return {p.position.x(), p.position.y(), p.position.z(), q.x(), q.y(), q.z(), q.w()};
}

}  // namespace cbtl::actions
