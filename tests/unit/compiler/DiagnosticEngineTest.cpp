// DiagnosticEngine: deterministic order whatever the order of reporting, the error limit, warnings as errors.
#include "compiler/diag/DiagnosticEngine.h"

#include <gtest/gtest.h>

namespace cbtl {
namespace {

TEST(DiagnosticEngine, SortsByFileOffsetSeverityCodeAndMessage) {
  DiagnosticEngine e;
  e.error("E0301", SourceRange{1, 5, 6}, "b");
  e.warning("W0201", SourceRange{0, 9, 10}, "unused");
  e.error("E0201", SourceRange{0, 9, 10}, "z");
  e.error("E0201", SourceRange{0, 9, 10}, "a");
  e.error("E0101", SourceRange{0, 2, 3}, "first");
  const auto out = e.sorted();
  ASSERT_EQ(out.size(), 5u);
  EXPECT_EQ(out[0].message, "first");  // file 0, offset 2
  EXPECT_EQ(out[1].message, "a");      // file 0, offset 9: errors before warnings, then code, then text
  EXPECT_EQ(out[2].message, "z");
  EXPECT_EQ(out[3].code, "W0201");
  EXPECT_EQ(out[4].range.file, 1u);  // file 1 last
}

TEST(DiagnosticEngine, OrderDoesNotDependOnReportingOrder) {
  DiagnosticEngine a, b;
  a.error("E0201", SourceRange{0, 1, 2}, "x");
  a.error("E0202", SourceRange{0, 1, 2}, "y");
  b.error("E0202", SourceRange{0, 1, 2}, "y");
  b.error("E0201", SourceRange{0, 1, 2}, "x");
  const auto sa = a.sorted(), sb = b.sorted();
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t i = 0; i < sa.size(); ++i) EXPECT_EQ(sa[i].code, sb[i].code);
}

TEST(DiagnosticEngine, ErrorLimitKeepsTheFirstErrorsAndCountsTheRest) {
  DiagnosticEngine e(2);
  for (int i = 0; i < 5; ++i) {
    e.error("E0201", SourceRange{0, static_cast<std::uint32_t>(10 - i), 11}, "e" + std::to_string(i))
        .note("ignored past the limit");
  }
  e.warning("W0201", SourceRange{0, 0, 1}, "warnings are not limited");
  EXPECT_EQ(e.errorCount(), 5u);
  EXPECT_EQ(e.droppedCount(), 3u);
  EXPECT_EQ(e.warningCount(), 1u);
  const auto out = e.sorted();
  ASSERT_EQ(out.size(), 3u);  // two errors (the first two reported) and the warning
  EXPECT_EQ(out[0].code, "W0201");
  EXPECT_EQ(out[1].message, "e1");
  EXPECT_EQ(out[2].message, "e0");
  EXPECT_TRUE(e.hasErrors());
}

TEST(DiagnosticEngine, WarningsAsErrorsPromotesAndCountsAgainstTheLimit) {
  DiagnosticEngine e(1);
  e.setWarningsAsErrors(true);
  e.warning("W0201", SourceRange{0, 0, 1}, "unused");
  e.warning("W0502", SourceRange{0, 2, 3}, "no sampler");
  EXPECT_EQ(e.errorCount(), 2u);
  EXPECT_EQ(e.warningCount(), 0u);
  EXPECT_EQ(e.droppedCount(), 1u);
  const auto out = e.sorted();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].severity, Severity::Error);
  EXPECT_EQ(out[0].code, "W0201");  // the code keeps its W
}

TEST(DiagnosticEngine, ChildrenStayAttached) {
  DiagnosticEngine e;
  e.error("E0202", SourceRange{0, 5, 6}, "twice").note("first here", SourceRange{0, 1, 2}).help("rename one");
  const auto out = e.sorted();
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].children.size(), 2u);
  EXPECT_EQ(out[0].children[0].kind, ChildKind::Note);
  EXPECT_TRUE(out[0].children[0].range.valid());
  EXPECT_EQ(out[0].children[1].kind, ChildKind::Help);
  EXPECT_FALSE(out[0].children[1].range.valid());
}

}  // namespace
}  // namespace cbtl
