// app/PlanReport.h's renderEvent: an event as `feedback` reads it back, bools as true/false with the declaration.
#include "app/PlanReport.h"

#include <gtest/gtest.h>

namespace {

TEST(PlanReport, EventsReadBackWithTheirDeclaredTypes) {
  cbtl::ir::ConstraintGraph graph;
  cbtl::ir::Function reaction;
  reaction.name = "cleaningReaction";
  reaction.kind = cbtl::ir::FunctionKind::Feedback;
  cbtl::ir::Param surface, welcome;
  surface.name = "surface";
  surface.type.kind = cbtl::ir::TypeKind::Enum;
  welcome.name = "welcome";
  welcome.type.kind = cbtl::ir::TypeKind::Bool;
  reaction.params = {surface, welcome};
  graph.feedback.push_back(reaction);
  const cbtl::sim::FeedbackEvent event{"cleaningReaction", {cbtl::sim::Value::name("table"), cbtl::sim::Value::num(1)}};
  EXPECT_EQ(cbtl::app::renderEvent(event, &graph), "cleaningReaction(table, true)");
  EXPECT_EQ(cbtl::app::renderEvent(event), "cleaningReaction(table, 1)") << "without the declaration: as sent";
  const cbtl::sim::FeedbackEvent unknown{"other", {cbtl::sim::Value::num(0)}};
  EXPECT_EQ(cbtl::app::renderEvent(unknown, &graph), "other(0)");
}

}  // namespace
