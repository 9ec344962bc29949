#include "domains/books/BooksSimulator.h"

#include "domains/home/HomeEpisode.h"
#include "domains/home/HomeScene.h"
#include "domains/home/HomeSurfaces.h"
#include "robot/actions/CallArguments.h"
#include "robot/actions/SurfaceGeometry.h"

#include <algorithm>
#include <stdexcept>

namespace cbtl::domains::books {

using sim::StepResult;
using sim::Value;

namespace {

// The simulator's user has no language-model judge, so its ground truth cannot fail.
bool enjoysBook(const BooksUser& user, const Book& book) {
  const auto enjoyed = user.enjoys(book);
  if (!enjoyed) throw std::logic_error("books: the user's taste failed: " + enjoyed.error().describe());
  return enjoyed.value();
}

// The parked slot home::emptyRoom gives `body` (book_k: slot k).
std::size_t parkingSlot(const std::string& body) {
  for (std::size_t k = 0; k < home::kBookCount; ++k)
    if (home::bookBody(k) == body) return k;
  return home::kBookCount;  // a catalogue body beyond the scene's books: the next free slot
}

}  // namespace

BooksSimulator::BooksSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed)
    : BooksSimulator(program, options, seed, BooksUser::paperDefault()) {}

BooksSimulator::BooksSimulator(const ProgramFacts& program, const sim::SimulatorOptions& options, std::uint64_t seed,
                               BooksUser user)
    // BooksShared's braces evaluate in order, so a program without a scene is told so before its catalogue is read.
    : BooksSimulator(std::make_shared<const BooksShared>(BooksShared{
                         home::programScene(program, "books"), BookCatalog::fromProgram(program), std::move(user)}),
                     options, sim::WorldRole::Training, seed) {}

BooksSimulator::BooksSimulator(std::shared_ptr<const BooksShared> shared, const sim::SimulatorOptions& options,
                               sim::WorldRole role, std::uint64_t seed)
    : SimulatorBase(
          shared, options, role,
          actions::RobotSimulator::Setup{"books", shared->scene, actions::RobotActions(), home::kCaregiverPatience}) {
  for (const Book& b : catalog().books()) {
    if (!scenePoses().count(b.body)) {
      throw std::invalid_argument("books: the body '" + b.body + "' of Book entry '" + b.entry +
                                  "' is not a movable object of the scene");
    }
  }
  const auto hand = home::userHandFrame(world().workspace());
  if (!hand) throw std::runtime_error("books: the home scene lacks the sites user_hand and handover_center");
  hand_ = *hand;
  reset(seed);
}

void BooksSimulator::stockShelves(world::WorldState& state, bool mayHold) {
  std::vector<std::size_t> books = rng_.permutation(home::kBookCount);
  const std::vector<std::size_t> slots = rng_.permutation(home::kBookCount);
  if (mayHold && rng_.uniform() < kHeldProbability) home::holdCarried(state, home::bookBody(books.back()));
  // A book in the robot's hand stays there; the others may go on the furniture.
  if (state.held) {
    books.erase(std::remove_if(books.begin(), books.end(),
                               [&](std::size_t b) { return home::bookBody(b) == state.held->object; }),
                books.end());
  }
  const std::size_t count = 3 + rng_.index(books.size() - 3 + 1);
  for (std::size_t i = 0; i < count; ++i) {
    state.objects[home::bookBody(books[i])] = scenePoses().at(home::bookBody(slots[i]));
  }
}

void BooksSimulator::reset(std::uint64_t seed) {
  rng_.seed(seed);
  judged_ = false;
  world::WorldState s = home::emptyRoom(scene(), scenePoses());
  if (isEvaluationTwin())
    stockForEvaluation(s);
  else
    stockShelves(s, true);
  startEpisode(s);
}

void BooksSimulator::stockForEvaluation(world::WorldState& state) {
  const std::vector<std::size_t> order = rng_.permutation(catalog().books().size());
  const std::vector<std::size_t> slots = rng_.permutation(home::kBookCount);
  std::vector<const Book*> enjoyed, others;
  for (std::size_t i : order) {
    const Book& b = catalog().books()[i];
    (enjoysBook(user(), b) ? enjoyed : others).push_back(&b);
  }
  if (enjoyed.size() > kEvalEnjoyed) enjoyed.resize(kEvalEnjoyed);
  if (others.size() > kEvalOthers) others.resize(kEvalOthers);
  std::size_t slot = 0;
  for (const auto* group : {&enjoyed, &others}) {
    for (const Book* b : *group) {
      if (slot < slots.size()) state.objects[b->body] = scenePoses().at(home::bookBody(slots[slot++]));
    }
  }
}

std::vector<std::string> BooksSimulator::pickable() const {
  const world::Workspace& ws = world().workspace();
  const std::vector<std::string> geoms = home::homeSurfaceGeoms();
  const std::string held = ws.state().held ? ws.state().held->object : std::string();
  std::vector<std::string> out;
  for (const Book& b : catalog().books()) {
    if (b.body == held) continue;
    if (actions::supportOf(world(), b.body, geoms)) out.emplace_back(b.entry);
  }
  return out;
}

sim::Observation BooksSimulator::observe() const {
  const world::WorldState& s = world().workspace().state();
  sim::Observation o;
  o["pickable"] = Value::names(pickable());
  o["handPose"] = Value::vec(actions::encodePose3(hand_));
  o["heldBody"] = Value::name(s.held ? s.held->object : std::string());
  return o;
}

std::string BooksSimulator::requestedTask() const {
  return world().workspace().state().held ? "stowThenHandOverBook" : "handOverBook";
}

StepResult BooksSimulator::afterFailure(StepResult step) {
  judged_ = false;
  return step;
}

StepResult BooksSimulator::afterApplied(const sim::ActionCall& call, const actions::RobotActionResult&,
                                        StepResult step) {
  if (call.name == "handOver") return handOver(std::move(step));
  if (call.name == "say" && call.args[0].text == kDoneUtterance && judged_) {
    step.taskDone = true;  // the robot has handed over, put its arm back and said so
    judged_ = false;
  }
  return step;
}

StepResult BooksSimulator::handOver(StepResult r) {
  world::Workspace& ws = world().workspace();
  const std::string body = ws.state().held->object;  // handOver succeeded, so something is held
  const Book* book = catalog().byBody(body);
  if (book == nullptr) {
    r.status = sim::ActionStatus::Ignored;
    r.taskDone = true;
    r.message = "handOver: the user does not take the " + body;
    return r;
  }
  judged_ = true;
  const Eigen::Vector3d point = ws.toolPose().position;
  const bool reached = user().reaches(hand_, point);
  const bool enjoyed = reached && enjoysBook(user(), *book);
  const std::string said = BooksUser::reaction(*book, reached, enjoyed);
  r.feedback.push_back(
      sim::FeedbackEvent{"handoverOutcome",
                         {Value::name(book->entry), Value::vec({point.x(), point.y(), point.z()}),
                          Value::num(reached ? 1 : 0), Value::name(said), Value::num(enjoyed ? 1 : 0)}});
  r.hasSatisfaction = true;
  r.satisfaction = reached && enjoyed ? 1.0 : -1.0;
  r.message = said;
  if (reached) {
    // The user takes the book: it leaves the robot's hand and the room.
    ws.setHeld(std::nullopt);
    world::WorldState s = ws.state();
    s.gripper = 1.0;
    s.objects[body] = home::parkedPose(parkingSlot(body));
    ws.setState(s);
  }
  restockWhenEmpty();
  return r;
}

void BooksSimulator::restockWhenEmpty() {
  if (!pickable().empty()) return;
  world::WorldState s = world().workspace().state();
  stockShelves(s, false);
  world().workspace().setState(s);
}

void BooksSimulator::caregiverReset() {
  world::WorldState s = world().workspace().state();
  home::caregiverReset(s, scene());
  setWorldState(s);
  restockWhenEmpty();
  judged_ = false;
}

}  // namespace cbtl::domains::books
