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
    : CleaningSimulator(home::programScene(program, "cleaning"), options,
                        std::make_shared<const CleaningUser>(std::move(user)), seed) {}

CleaningSimulator::CleaningSimulator(std::shared_ptr<const world::Scene> scene, const sim::SimulatorOptions& options,
                                     std::shared_ptr<const CleaningUser> user, std::uint64_t seed)
    : options_(options),
      scene_(std::move(scene)),
      user_(std::move(user)),
      world_(std::make_unique<world::World>(scene_)) {
  scenePoses_ = world_->workspace().state().objects;
  reset(seed);
}

void CleaningSimulator::reset(std::uint64_t seed) {
  rng_.seed(seed);
  judged_ = false;
  idleRun_ = 0;
  world_->utterances().clear();
  world::WorldState s = home::emptyRoom(*scene_, scenePoses_);
  const std::vector<std::size_t> books = rng_.permutation(home::kBookCount);
  const double held = rng_.uniform();
  if (held >= 2.0 / 3.0) {
    home::holdCarried(s, home::bookBody(books[1]));
  } else if (held >= 1.0 / 3.0) {
    home::holdCarried(s, "duster");
  }
  if (world_->workspace().setState(s) != world::StateStatus::Ok) {
    throw std::logic_error("cleaning: the episode's start state is invalid");  // a bug in this file
  }
  obstacle_ = home::bookBody(books[0]);
  coverOneSurface();
}

void CleaningSimulator::coverOneSurface() {
  world::Workspace& ws = world_->workspace();
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
    if (const auto pose = world::builtins::samplePlacement(*world_, obstacle_, covered, kObstacleClearance, rng_)) {
      ws.setObjectPose(obstacle_, *pose);
      break;
    }
  }
}

std::vector<std::string> CleaningSimulator::clearSurfaces() const {
  const world::Workspace& ws = world_->workspace();
  const std::vector<std::string> geoms = home::homeSurfaceGeoms();
  std::vector<bool> clear(geoms.size(), true);
  const std::string held = ws.state().held ? ws.state().held->object : std::string();
  for (const world::ObjectInfo& o : ws.scene().objects()) {
    if (o.name == "duster" || o.name == held) continue;
    if (const auto support = actions::supportOf(*world_, o.name, geoms)) {
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
  const world::WorldState& s = world_->workspace().state();
  sim::Observation o;
  o["clearSurfaces"] = Value::names(clearSurfaces());
  o["heldBody"] = Value::name(s.held ? s.held->object : std::string());
  o["basePose"] = Value::vec({s.base.x, s.base.y, s.base.yaw});
  return o;
}

std::string CleaningSimulator::requestedTask() const {
  const auto& held = world_->workspace().state().held;
  if (!held) return "cleanSurface";
  return held->object == "duster" ? "cleanWithDusterInHand" : "stowThenClean";
}

StepResult CleaningSimulator::act(const sim::ActionCall& call) {
  idleRun_ = 0;
  const auto done = actions_.execute(*world_, call);
  if (!done) {
    StepResult r;
    r.status = sim::ActionStatus::UnknownAction;
    r.message = "cleaning has no action '" + call.name + "'";
    return r;
  }
  StepResult r = done->toStepResult(call.name);
  if (!done->wellFormed) return r;
  if (!done->done()) {
    r.taskDone = true;  // a failure ends the task
    r.taskFailed = true;
    judged_ = false;
    coverOneSurface();  // the next task
    return r;
  }
  if (call.name == "say" && call.args[0].text == kDoneUtterance && judged_) {
    r.taskDone = true;  // the robot has cleaned, put its arm back and said so
    judged_ = false;
    coverOneSurface();  // the next task
    return r;
  }
  if (call.name == "wipe") {
    if (const auto surface = home::surfaceMemberOfGeom(call.args[0].text)) {
      const bool welcome = user_->welcomes(*surface);
      r.feedback.push_back(
          sim::FeedbackEvent{"cleaningReaction", {Value::name(*surface), Value::num(welcome ? 1 : 0)}});
      r.hasSatisfaction = true;
      r.satisfaction = welcome ? 1.0 : -1.0;
      r.message = welcome ? "Thanks for cleaning there." : "Don't clean there -- I can do it myself.";
      judged_ = true;
    }
  }
  return r;
}

StepResult CleaningSimulator::idle() {
  StepResult r;
  r.consumedStep = true;
  r.message = "idle: the robot waits";
  if (++idleRun_ >= home::kCaregiverPatience) {
    world::WorldState s = world_->workspace().state();
    home::caregiverReset(s, *scene_);
    world_->workspace().setState(s);
    idleRun_ = 0;
    judged_ = false;
    coverOneSurface();
    r.caregiverReset = true;
    r.message = "the robot was stuck: the caregiver put it back at its start";
  }
  return r;
}

std::unique_ptr<sim::DomainSimulator> CleaningSimulator::makeEvaluationTwin() const {
  return std::unique_ptr<sim::DomainSimulator>(new CleaningSimulator(scene_, options_, user_, 0));
}

}  // namespace cbtl::domains::cleaning
