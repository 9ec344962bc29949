// A skill's `allow` blocks: every call made inside one carries its exception to the world's clearances (the
// clearance's bodies, or the text the target evaluates to, with the distance in metres and where it was declared),
// nested blocks outermost first; calls outside carry none.
#include "tests/unit/runtime/TestPrograms.h"

#include "runtime/approach/ActionPlan.h"

#include <gtest/gtest.h>

#include <string>

namespace cbtl::approach {
namespace {

std::string allowProgram() {
  return std::string(R"(domain allowplan;
import std.actions;
world ")") +
         CBTL_DOMAINS_DIR + R"(/home/home.xml";
clearance person: "user" >= 5 cm;
skill wipeIt(surface: text) {
  do {
    say("outside");
    allow held near person 1 cm {
      say("one");
      allow gripper touch surface 2 mm { say("two"); }
    }
    for i in 0 .. 1 { allow robot near "bed" 3 mm { wait(1); } }
  }
}
task t {
  var face : text in ["table_top"] = "table_top";
  run wipeIt(face);
}
)";
}

TEST(ActionPlan, CallsInsideAllowBlocksCarryTheirExceptions) {
  auto lp = test::compileOrFail("allowplan.cbtl", allowProgram());
  ASSERT_TRUE(lp->ok());
  rt::Program& program = lp->program();
  const TaskActions actions(program, program.graph().tasks.at(0));
  const std::vector<double> observation(program.observationWidth(), 0.0);
  const auto calls = actions.unroll(program, program.initialAssignment(observation), observation);
  ASSERT_EQ(calls.size(), 5u);
  EXPECT_EQ(calls[0].name, "say");
  EXPECT_TRUE(calls[0].exceptions.empty());

  ASSERT_EQ(calls[1].exceptions.size(), 1u);
  const sim::ClearanceException& person = calls[1].exceptions[0];
  EXPECT_EQ(person.part, "held");
  EXPECT_EQ(person.names, std::vector<std::string>{"user"});
  EXPECT_DOUBLE_EQ(person.separation, 0.01);
  EXPECT_EQ(person.declaredAt, "allowplan.cbtl:8:5");

  ASSERT_EQ(calls[2].exceptions.size(), 2u);  // nested: the outer one first
  EXPECT_EQ(calls[2].exceptions[0], person);
  EXPECT_EQ(calls[2].exceptions[1].part, "gripper");
  EXPECT_EQ(calls[2].exceptions[1].names, std::vector<std::string>{"table_top"});  // the parameter's value
  EXPECT_DOUBLE_EQ(calls[2].exceptions[1].separation, -0.002);                     // touch: a depth

  for (std::size_t i = 3; i < 5; ++i) {
    EXPECT_EQ(calls[i].name, "wait");
    ASSERT_EQ(calls[i].exceptions.size(), 1u);
    EXPECT_EQ(calls[i].exceptions[0].part, "robot");
    EXPECT_EQ(calls[i].exceptions[0].names, std::vector<std::string>{"bed"});
    EXPECT_DOUBLE_EQ(calls[i].exceptions[0].separation, 0.003);
  }
}

}  // namespace
}  // namespace cbtl::approach
