// WorldBuiltins.h — binds the robot world (robot/world) to the built-ins std.kinova, std.collision and
// std.occlusion declare: forward and inverse kinematics, IK samplers, collision, placement and clearance
// checks, occlusion, motion-plan feasibility, scene queries.
//
// Semantics beyond the stdlib comments (docs/world.md, "Built-ins"):
// - Every call starts from the WorldHost's reference state (WorldHost.h) and leaves no trace.
// - Functions are deterministic: those that search (ikExists, motionPlanExists, basePathExists) draw from an
//   RNG seeded with a fixed value on every call, so the same arguments give the same answer. Samplers draw
//   their seeds from the solver's Rng.
// - Bad names (an unknown body, site, surface or named configuration) make predicates false, distances
//   +infinity and poses/configurations NaN (every check on a NaN value fails); samplers fail.
// - Budgets: feasibility planning uses at most `planIterations` RRTConnect iterations; IK uses the World's
//   IkOptions. Iteration counts only.
#pragma once

#include "runtime/core/Builtins.h"

#include <memory>
#include <string>
#include <vector>

namespace cbtl::world {
class Scene;
struct WorldState;
}  // namespace cbtl::world
namespace cbtl::actions {
class RobotActions;
}

namespace cbtl::bind {

struct WorldBuiltinOptions {
  int planIterations = 3000;  // RRTConnect iterations of motionPlanExists / basePathExists
  int ikAttempts = 10;        // IK attempts (1 + restarts) of ikExists and the IK samplers
};

// `builtins` plus the world built-ins over `scene`, with a new WorldHost as the registry's host.
rt::Builtins withWorld(rt::Builtins builtins, std::shared_ptr<const world::Scene> scene,
                       const WorldBuiltinOptions& options = {});

// Loads the MJCF scene at `path` and adds the world built-ins over it to `builtins`. false, with MuJoCo's or
// the scene checker's message in `error` (which names the file), when the scene cannot be loaded.
bool addWorldFromFile(rt::Builtins& builtins, const std::string& path, std::string& error,
                      const WorldBuiltinOptions& options = {});

// Makes `state` the world the built-ins of `host` (a registry's host made by withWorld) read. false when the
// host is not a world host or the state does not fit its scene (unknown object, joints out of limits).
bool setWorldReference(rt::BuiltinHost* host, const world::WorldState& state);

// Makes `executor` (the domain's actions plus the standard ones) the one the world model of `host` dry-runs
// plans with (runtime/sim/ExecutionModel.h). false when the host is not a world host.
bool setWorldExecutor(rt::BuiltinHost* host, std::shared_ptr<const actions::RobotActions> executor);

// Names of every function and sampler withWorld adds (to tell "needs a world" from "unknown").
std::vector<std::string> worldBuiltinNames();

}  // namespace cbtl::bind
