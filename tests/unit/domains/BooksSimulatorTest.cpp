// The Books simulator: episode starts, observations, requested tasks, handovers the user reaches or not,
// and the evaluation twin.
#include "domains/books/BooksSimulator.h"

#include "domains/books/BookCatalog.h"
#include "robot/actions/CallArguments.h"
#include "tests/unit/domains/HomeTestSupport.h"
#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace {

using cbtl::domains::books::BooksSimulator;
using cbtl::domains::books::BooksUser;
using cbtl::domains::books::Interval;
using cbtl::sim::ActionCall;
using cbtl::sim::ActionStatus;
using cbtl::sim::StepResult;
using cbtl::sim::Value;
namespace actions = cbtl::actions;
namespace home = cbtl::domains::home;
namespace world = cbtl::world;

const world::Pose2 kBedBase{1.0, 0.2, 0.0};

// books.cbtl's facts: the home scene and the Book catalogue.
const cbtl::domains::ProgramFacts& books() { return cbtl::test::programFacts("books"); }

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// The robot at the bed holding `body` with the tool `radius` metres from the user's ROM centre.
std::optional<Eigen::Vector3d> presentAt(BooksSimulator& sim, const std::string& body, double radius, world::Rng& rng) {
  if (!cbtl::test::holdAt(sim.world(), body, kBedBase)) return std::nullopt;
  return cbtl::test::handoverAt(sim.world(), BooksUser::romCentre(sim.handFrame()), radius, rng);
}

TEST(BooksSimulator, ResetIsDeterministic) {
  BooksSimulator a(books(), {}, 21), b(books(), {}, 4);
  b.reset(21);
  EXPECT_EQ(a.observe().at("pickable").members, b.observe().at("pickable").members);
  EXPECT_EQ(a.observe().at("heldBody").text, b.observe().at("heldBody").text);
  for (const auto& [name, pose] : a.worldState()->objects)
    EXPECT_EQ(pose.position, b.worldState()->objects.at(name).position) << name;
}

TEST(BooksSimulator, ObservationsHaveTheDeclaredNamesAndKinds) {
  BooksSimulator sim(books(), {}, 2);
  const auto o = sim.observe();
  ASSERT_EQ(o.size(), 3u);
  ASSERT_EQ(o.at("pickable").kind, Value::Kind::Names);
  for (const std::string& e : o.at("pickable").members) EXPECT_NE(sim.catalog().byEntry(e), nullptr) << e;
  ASSERT_EQ(o.at("handPose").kind, Value::Kind::Vector);
  ASSERT_EQ(o.at("handPose").vector.size(), 7u);
  EXPECT_EQ(o.at("heldBody").kind, Value::Kind::Name);
  // books.cbtl's romCentre(): the hand moved 0.2 m along its z lands on the scene's handover_center.
  const auto hand = actions::decodePose3(o.at("handPose").vector);
  ASSERT_TRUE(hand.has_value());
  const Eigen::Vector3d centre = hand->transformPoint(Eigen::Vector3d(0, 0, 0.2));
  EXPECT_LT((centre - sim.world().workspace().sitePose("handover_center")->position).norm(), 0.005);
}

TEST(BooksSimulator, EpisodesVaryTheShelfAndTheHeldBookWithValidStarts) {
  BooksSimulator sim(books(), {}, 0);
  std::set<std::string> tasks;
  std::set<std::size_t> counts;
  for (std::uint64_t seed = 0; seed < 30; ++seed) {
    sim.reset(seed);
    const auto o = sim.observe();
    const auto& pickable = o.at("pickable").members;
    counts.insert(pickable.size());
    EXPECT_GE(pickable.size(), 3u);
    const std::string held = o.at("heldBody").text;
    EXPECT_EQ(sim.requestedTask(), held.empty() ? "handOverBook" : "stowThenHandOverBook");
    if (!held.empty()) {
      const auto* book = sim.catalog().byBody(held);
      ASSERT_NE(book, nullptr) << held;
      EXPECT_FALSE(contains(pickable, book->entry));
    }
    tasks.insert(sim.requestedTask());
    EXPECT_TRUE(world::checkRobotCollisions(sim.world().workspace()).free()) << "seed " << seed;
  }
  EXPECT_EQ(tasks.size(), 2u);
  EXPECT_GE(counts.size(), 3u);
}

TEST(BooksSimulator, AReachableHandoverOfALikedBookPleasesTheUser) {
  BooksSimulator sim(books(), {}, 3);
  world::Rng rng(8);
  const auto point = presentAt(sim, "book_0", 0.2, rng);  // Cosmos, mid-shell
  ASSERT_TRUE(point.has_value());
  // Another book on the top shelf, so taking Cosmos does not empty the furniture (no restock).
  sim.world().workspace().setObjectPose("book_5", world::Pose3::fromPosition(Eigen::Vector3d(0.2, 0.75, 0.53)));
  ASSERT_EQ(sim.pickable(), (std::vector<std::string>{"intoTheWild"}));
  const StepResult r = sim.act(ActionCall{"handOver", {}});
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_TRUE(r.consumedStep);
  EXPECT_FALSE(r.taskDone) << "the task ends when the robot says Done";
  ASSERT_TRUE(r.hasSatisfaction);
  EXPECT_EQ(r.satisfaction, 1.0);
  ASSERT_EQ(r.feedback.size(), 1u);
  const auto& f = r.feedback[0];
  EXPECT_EQ(f.name, "handoverOutcome");
  ASSERT_EQ(f.args.size(), 5u);
  EXPECT_EQ(f.args[0].text, "cosmos");
  ASSERT_EQ(f.args[1].vector.size(), 3u);
  EXPECT_NEAR(f.args[1].vector[0], point->x(), 1e-9);
  EXPECT_EQ(f.args[2].number, 1.0);
  EXPECT_EQ(f.args[3].text, "Thank you, I love Cosmos!");
  EXPECT_EQ(f.args[4].number, 1.0);
  // The user took it.
  EXPECT_FALSE(sim.worldState()->held.has_value());
  EXPECT_FALSE(contains(sim.pickable(), "cosmos"));
  EXPECT_TRUE(home::isParked(sim.worldState()->objects.at("book_0")));
  EXPECT_EQ(sim.world().utterances().back(), "Here you go!");
  const StepResult done = sim.act(ActionCall{"say", {Value::name("Done")}});
  EXPECT_TRUE(done.taskDone);
}

TEST(BooksSimulator, AReachedDislikedBookIsTakenButDisappoints) {
  BooksSimulator sim(books(), {}, 3);
  world::Rng rng(8);
  ASSERT_TRUE(presentAt(sim, "book_6", 0.2, rng).has_value());  // Moby Dick
  const StepResult r = sim.act(ActionCall{"handOver", {}});
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_EQ(r.satisfaction, -1.0);
  EXPECT_EQ(r.feedback.at(0).args.at(2).number, 1.0);
  EXPECT_EQ(r.feedback.at(0).args.at(4).number, 0.0);
  EXPECT_FALSE(sim.worldState()->held.has_value());
}

TEST(BooksSimulator, AnUnreachableHandoverKeepsTheBookInHand) {
  BooksSimulator sim(books(), {}, 3);
  world::Rng rng(8);
  ASSERT_TRUE(presentAt(sim, "book_0", 0.45, rng).has_value());  // beyond the 0.3 m shell
  const StepResult r = sim.act(ActionCall{"handOver", {}});
  ASSERT_EQ(r.status, ActionStatus::Applied) << r.message;
  EXPECT_FALSE(r.taskDone);
  EXPECT_EQ(r.satisfaction, -1.0);
  EXPECT_EQ(r.feedback.at(0).args.at(2).number, 0.0);
  EXPECT_EQ(r.feedback.at(0).args.at(3).text, "I can't reach there.");
  EXPECT_EQ(r.feedback.at(0).args.at(4).number, 0.0);
  ASSERT_TRUE(sim.worldState()->held.has_value());
  EXPECT_EQ(sim.worldState()->held->object, "book_0");
  EXPECT_EQ(sim.requestedTask(), "stowThenHandOverBook");
}

TEST(BooksSimulator, HandingOverWithoutABookIsNotAHandover) {
  BooksSimulator sim(books(), {}, 3);
  world::WorldState s = *sim.worldState();
  s.held.reset();
  sim.world().workspace().setState(s);
  StepResult r = sim.act(ActionCall{"handOver", {}});
  EXPECT_EQ(r.status, ActionStatus::Ignored);  // NotHolding
  EXPECT_TRUE(r.taskDone);
  EXPECT_FALSE(r.hasSatisfaction);
  ASSERT_TRUE(cbtl::test::holdAt(sim.world(), "duster", kBedBase));
  r = sim.act(ActionCall{"handOver", {}});
  EXPECT_EQ(r.status, ActionStatus::Ignored);
  EXPECT_TRUE(r.feedback.empty());
  EXPECT_FALSE(r.hasSatisfaction);
}

TEST(BooksSimulator, TakingTheLastBookRestocksTheShelves) {
  BooksSimulator sim(books(), {}, 3);
  world::Rng rng(8);
  ASSERT_TRUE(presentAt(sim, "book_1", 0.2, rng).has_value());  // every other book is parked
  EXPECT_TRUE(sim.pickable().empty());
  const StepResult r = sim.act(ActionCall{"handOver", {}});
  ASSERT_EQ(r.satisfaction, 1.0) << r.message;
  EXPECT_GE(sim.pickable().size(), 3u);
}

TEST(BooksSimulator, TheCatalogueIsTheProgramsBookEntries) {
  BooksSimulator sim(books(), {}, 1);
  const auto* set = cbtl::domains::firstItemSetOfType(books(), "Book");
  ASSERT_NE(set, nullptr);
  ASSERT_EQ(sim.catalog().size(), set->entries.size());
  for (std::size_t i = 0; i < set->entries.size(); ++i) EXPECT_EQ(sim.catalog().books()[i].entry, set->entries[i].name);
  const auto* cosmos = sim.catalog().byEntry("cosmos");
  ASSERT_NE(cosmos, nullptr);
  EXPECT_EQ(cosmos->title, "Cosmos");
  EXPECT_EQ(cosmos->body, "book_0");
  EXPECT_EQ(cosmos->item.descriptors.at("tags"),
            (std::vector<std::string>{"nonfiction", "science", "astronomy", "universe"}));
}

TEST(BooksSimulator, WithoutASceneOrCatalogueItIsAClearError) {
  EXPECT_THROW(BooksSimulator(cbtl::domains::ProgramFacts{}, {}, 1), std::invalid_argument);
  cbtl::domains::ProgramFacts sceneOnly = books();
  sceneOnly.itemSets.clear();
  EXPECT_THROW(BooksSimulator(sceneOnly, {}, 1), std::invalid_argument);
}

TEST(BooksSimulator, EvaluationEpisodesOfferOneEnjoyedBookAmongFive) {
  // The hidden user enjoys Cosmos and Pride and Prejudice; a held-out task holds nothing and stocks one of them
  // with four other books, so an evaluation measures whether the robot picks the enjoyed one.
  BooksSimulator sim(books(), {}, 1);
  auto twin = sim.makeEvaluationTwin();
  const std::set<std::string> enjoyed{"cosmos", "prideAndPrejudice"};
  std::set<std::string> enjoyedSeen;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    twin->reset(seed);
    const auto o = twin->observe();
    EXPECT_EQ(o.at("heldBody").text, "") << "seed " << seed;
    const auto& pickable = o.at("pickable").members;
    ASSERT_EQ(pickable.size(), 5u) << "seed " << seed;
    int liked = 0;
    for (const std::string& b : pickable) {
      if (enjoyed.count(b)) {
        ++liked;
        enjoyedSeen.insert(b);
      }
    }
    EXPECT_EQ(liked, 1) << "seed " << seed;
  }
  EXPECT_EQ(enjoyedSeen, enjoyed) << "both enjoyed books occur across held-out tasks";
  // Training episodes keep the paper's random subset (3-9 books, sometimes one in hand).
  std::set<std::size_t> sizes;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    sim.reset(seed);
    sizes.insert(sim.observe().at("pickable").members.size());
  }
  EXPECT_GT(sizes.size(), 2u);
}

TEST(BooksSimulator, ACaregiverResetsARobotThatStaysIdle) {
  BooksSimulator sim(books(), {}, 2);
  world::Rng rng(5);
  ASSERT_TRUE(presentAt(sim, "book_4", 0.5, rng).has_value());  // holding a book at the bed
  for (int i = 1; i < home::kCaregiverPatience; ++i) EXPECT_FALSE(sim.idle().caregiverReset) << i;
  const StepResult r = sim.idle();
  EXPECT_TRUE(r.caregiverReset);
  const world::WorldState& s = *sim.worldState();
  EXPECT_EQ(s.base.x, 0.0);
  EXPECT_EQ(s.base.y, 0.0);
  EXPECT_FALSE(s.held.has_value()) << "the caregiver takes the book the robot was stuck with";
  EXPECT_FALSE(sim.observe().at("pickable").members.empty()) << "and the furniture holds books";
  EXPECT_FALSE(sim.idle().caregiverReset) << "the count starts again";
}

TEST(BooksSimulator, EvaluationTwinSharesTheUserNotTheWorld) {
  const BooksUser mobyDickOnly(cbtl::textpref::SimulatedUser("moby", "I only like Moby Dick.", {{{"item=mobyDick"}}}),
                               Interval{0.0, 1.0});
  BooksSimulator sim(books(), {}, 3, mobyDickOnly);
  auto twin = sim.makeEvaluationTwin();
  auto* t = dynamic_cast<BooksSimulator*>(twin.get());
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(&t->user(), &sim.user());
  world::Rng rng(8);
  ASSERT_TRUE(presentAt(*t, "book_6", 0.2, rng).has_value());
  const auto trainHeld = sim.worldState()->held;
  const StepResult r = t->act(ActionCall{"handOver", {}});
  EXPECT_EQ(r.satisfaction, 1.0);  // this user likes Moby Dick
  EXPECT_EQ(sim.worldState()->held.has_value(), trainHeld.has_value());
}

}  // namespace
