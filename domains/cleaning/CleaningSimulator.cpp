#include "domains/cleaning/CleaningSimulator.h"

#include "domains/home/HomeEpisode.h"
#include "domains/home/HomeScene.h"
#include "domains/home/HomeSurfaces.h"
#include "robot/actions/SurfaceGeometry.h"

#include <stdexcept>

namespace cbtl::domains::cleaning {

using sim::StepResult;
using sim::Value;

CleaningSimulator::CleaningSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options,
                                     std::uint64_t seed)
    : CleaningSimulator(program, options, seed, CleaningUser::paperDefault()) {}

CleaningSimulator::CleaningSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options,
                                     std::uint64_t seed, CleaningUser user)
    : CleaningSimulator(std::make_shared<const CleaningShared>(
                            CleaningShared{home::programScene(program, "cleaning"), std::move(user)}),
                        options, sim::WorldRole::Training, seed) {}

CleaningSimulator::CleaningSimulator(std::shared_ptr<const CleaningShared> shared, const sim::SimulatorOptions& options,
                                     sim::WorldRole role, std::uint64_t seed)
    : SimulatorBase(shared, options, role,
                    actions::RobotSimulator::Setup{"cleaning", shared->scene, actions::RobotActions(),
                                                   home::kCaregiverPatience}) {
  reset(seed);
}

void CleaningSimulator::reset(std::uint64_t seed) {
  rng_.seed(seed);
  judged_ = false;
  world::WorldState s = home::emptyRoom(scene(), scenePoses());
  const std::vector<std::size_t> books = rng_.permutation(home::kBookCount);
  const double held = rng_.uniform();
  if (held >= 2.0 / 3.0) {
    home::holdCarried(s, home::bookBody(books[1]));
  } else if (held >= 1.0 / 3.0) {
    home::holdCarried(s, "duster");
  }
  startEpisode(s);
  obstacle_ = home::bookBody(books[0]);
  coverOneSurface();
}

void CleaningSimulator::coverOneSurface() {
  world::Workspace& ws = world().workspace();
  // The books lying around (a book the robot put away) are tidied up first.
  const std::string held = ws.state().held ? ws.state().held->object : std::string();
  for (std::size_t k = 0; k < home::kBookCount; ++k) {
    const std::string body = home::bookBody(k);
    if (body != held && ws.objectPose(body) && !home::isParked(*ws.objectPose(body)))
      ws.setObjectPose(body, home::parkedPose(k));
  }
  if (obstacle_ == held) return;
  // Surfaces in a uniform order: the first one with room for the book is covered (the main table may have
  // none while the duster lies on it).
  for (std::size_t i : rng_.permutation(home::kHomeSurfaces.size())) {
    const std::string covered(home::kHomeSurfaces[i].geom);
    if (const auto pose = world::builtins::samplePlacement(world(), obstacle_, covered, kObstacleClearance, rng_)) {
      ws.setObjectPose(obstacle_, *pose);
      break;
    }
  }
}

std::vector<std::string> CleaningSimulator::clearSurfaces() const {
  const world::Workspace& ws = world().workspace();
  const std::vector<std::string> geoms = home::homeSurfaceGeoms();
  std::vector<bool> clear(geoms.size(), true);
  const std::string held = ws.state().held ? ws.state().held->object : std::string();
  for (const world::ObjectInfo& o : ws.scene().objects()) {
    if (o.name == "duster" || o.name == held) continue;
    if (const auto support = actions::supportOf(world(), o.name, geoms)) {
      for (std::size_t i = 0; i < geoms.size(); ++i)
        if (geoms[i] == *support) clear[i] = false;
    }
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < geoms.size(); ++i)
    if (clear[i]) out.emplace_back(home::kHomeSurfaces[i].member);
  return out;
}

sim::Observation CleaningSimulator::observe() const {
  const world::WorldState& s = world().workspace().state();
  sim::Observation o;
  o["clearSurfaces"] = Value::names(clearSurfaces());
  o["heldBody"] = Value::name(s.held ? s.held->object : std::string());
  o["basePose"] = Value::vec({s.base.x, s.base.y, s.base.yaw});
  return o;
}

std::string CleaningSimulator::requestedTask() const {
  const auto& held = world().workspace().state().held;
  if (!held) return "cleanSurface";
  return held->object == "duster" ? "cleanWithDusterInHand" : "stowThenClean";
}

StepResult CleaningSimulator::afterFailure(StepResult step) {
  judged_ = false;
  coverOneSurface();  // the next task
  return step;
}

StepResult CleaningSimulator::afterApplied(const sim::ActionCall& call, const actions::RobotActionResult&,
                                           StepResult step) {
  if (call.name == "say" && call.args[0].text == kDoneUtterance && judged_) {
    step.taskDone = true;  // the robot has cleaned, put its arm back and said so
    judged_ = false;
    coverOneSurface();  // the next task
    return step;
  }
  if (call.name == "wipe") {
    if (const auto surface = home::surfaceMemberOfGeom(call.args[0].text)) {
      const bool welcome = user().welcomes(*surface);
      step.feedback.push_back(
          sim::FeedbackEvent{"cleaningReaction", {Value::name(*surface), Value::num(welcome ? 1 : 0)}});
      step.hasSatisfaction = true;
      step.satisfaction = welcome ? 1.0 : -1.0;
      step.message = welcome ? "Thanks for cleaning there." : "Don't clean there -- I can do it myself.";
      judged_ = true;
    }
  }
  return step;
}

void CleaningSimulator::caregiverReset() {
  world::WorldState s = world().workspace().state();
  home::caregiverReset(s, scene());
  setWorldState(s);
  judged_ = false;
  coverOneSurface();
}

}  // namespace cbtl::domains::cleaning
