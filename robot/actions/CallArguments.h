// CallArguments.h — checking the shape of a sim::ActionCall and decoding its values into robot-world types.
//
// Value layouts (DomainSimulator.h): SE3 = (x, y, z, qx, qy, qz, qw) in metres and a quaternion, SE2 =
// (x, y, yaw) in metres and radians, Conf = the 7 joint angles in radians, vec<N> = N numbers.
// Shape errors (count, kind, vector length) are a domain/compiler bug and are reported as messages; values
// of the right shape but unusable (NaN, a zero quaternion) are the plan's problem and are decoded to
// nullopt so the caller can fail the action explicitly.
#pragma once

#include "robot/world/Pose.h"
#include "runtime/sim/DomainSimulator.h"

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::actions {

// "a number", "a vector", "a name", "a set of names".
const char* kindName(sim::Value::Kind kind);

// The expected shape of one argument: its kind and, for vectors, its length (0: any length).
struct ArgShape {
  sim::Value::Kind kind = sim::Value::Kind::Number;
  std::size_t length = 0;
};

// Empty when `call` has exactly these arguments; otherwise a message naming the call and the first misfit.
std::string checkArguments(const sim::ActionCall& call, std::initializer_list<ArgShape> shapes);

inline constexpr ArgShape kNumberArg{sim::Value::Kind::Number, 0};
inline constexpr ArgShape kNameArg{sim::Value::Kind::Name, 0};
inline constexpr ArgShape kSe3Arg{sim::Value::Kind::Vector, 7};
inline constexpr ArgShape kSe2Arg{sim::Value::Kind::Vector, 3};
inline constexpr ArgShape kConfArg{sim::Value::Kind::Vector, world::kArmDof};
inline constexpr ArgShape kVec2Arg{sim::Value::Kind::Vector, 2};

// Decoders of well-shaped vectors; nullopt when a component is not finite (and, for SE3, when the quaternion
// has (near) zero norm; other quaternions are normalised).
std::optional<world::Pose3> decodePose3(const std::vector<double>& v);
std::optional<world::Pose2> decodePose2(const std::vector<double>& v);
std::optional<world::ArmConfig> decodeConf(const std::vector<double>& v);

// The encoder in the same layout (observations of a pose).
std::vector<double> encodePose3(const world::Pose3& p);

}  // namespace cbtl::actions
