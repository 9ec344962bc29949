// Diagnostic rendering: the text layout (location, excerpt, caret, children) and the JSON object shape
// that tools rely on (docs/diagnostics.md).
#include "compiler/diag/DiagnosticRenderer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cbtl {
namespace {

struct Rendering : ::testing::Test {
  SourceManager sm;
  FileId file = sm.add("dir/case.cbtl", "var x : reel;\nrequire ñx < 1;\n");
};

TEST_F(Rendering, TextHasLocationExcerptCaretAndChildren) {
  Diagnostic d{Severity::Error, "E0206", SourceRange{file, 8, 12}, "unknown type 'reel'", {}};
  d.help("did you mean 'real'?");
  d.note("declared here", SourceRange{file, 4, 5});
  const std::string text = renderDiagnosticText(d, sm);
  EXPECT_EQ(text,
            "dir/case.cbtl:1:9: error[E0206]: unknown type 'reel'\n"
            "   |\n"
            " 1 | var x : reel;\n"
            "   |         ^~~~\n"
            "  = help: did you mean 'real'?\n"
            "dir/case.cbtl:1:5: note: declared here\n"
            "   |\n"
            " 1 | var x : reel;\n"
            "   |     ^\n");
}

TEST_F(Rendering, CaretColumnsCountCodePoints) {
  // 'x' after 'ñ' (2 bytes) on line 2: byte 24, column 10.
  Diagnostic d{Severity::Warning, "W0201", SourceRange{file, 24, 25}, "w", {}};
  const std::string text = renderDiagnosticText(d, sm);
  EXPECT_NE(text.find("dir/case.cbtl:2:10: warning[W0201]: w\n"), std::string::npos) << text;
  EXPECT_NE(text.find("   |          ^\n"), std::string::npos) << text;
}

TEST_F(Rendering, SpansOverSeveralLinesUnderlineToTheEndOfTheFirst) {
  Diagnostic d{Severity::Error, "E0301", SourceRange{file, 4, 20}, "m", {}};
  const std::string text = renderDiagnosticText(d, sm);
  EXPECT_NE(text.find("   |     ^~~~~~~~~\n"), std::string::npos) << text;  // "x : reel;", 9 columns
}

TEST_F(Rendering, JsonIsOneObjectPerLineWithTheDocumentedFields) {
  Diagnostic d{Severity::Error, "E0206", SourceRange{file, 8, 12}, "unknown type 'reel'", {}};
  d.help("did you mean 'real'?");
  d.note("declared here", SourceRange{file, 4, 5});
  const std::string line = renderDiagnosticJson(d, sm);
  EXPECT_EQ(line.find('\n'), std::string::npos);
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(j.at("severity"), "error");
  EXPECT_EQ(j.at("code"), "E0206");
  EXPECT_EQ(j.at("message"), "unknown type 'reel'");
  const auto& span = j.at("span");
  EXPECT_EQ(span.at("file"), "dir/case.cbtl");
  EXPECT_EQ(span.at("line"), 1);
  EXPECT_EQ(span.at("column"), 9);
  EXPECT_EQ(span.at("end_line"), 1);
  EXPECT_EQ(span.at("end_column"), 13);
  EXPECT_EQ(span.at("byte_start"), 8);
  EXPECT_EQ(span.at("byte_end"), 12);
  ASSERT_EQ(j.at("children").size(), 2u);
  EXPECT_EQ(j["children"][0].at("kind"), "help");
  EXPECT_FALSE(j["children"][0].contains("span"));  // a child without a location has no span
  EXPECT_EQ(j["children"][1].at("kind"), "note");
  EXPECT_EQ(j["children"][1].at("span").at("column"), 5);
  EXPECT_EQ(j.at("rendered"), renderDiagnosticText(d, sm));
  EXPECT_EQ(j.size(), 6u);  // severity, code, message, span, children, rendered
}

TEST_F(Rendering, JsonStaysValidForInvalidUtf8) {
  SourceManager raw;
  const FileId f = raw.add("bad.cbtl", std::string("var \xff;\n"));
  Diagnostic d{Severity::Error, "E0105", SourceRange{f, 4, 5}, "not UTF-8", {}};
  nlohmann::json j;
  EXPECT_NO_THROW(j = nlohmann::json::parse(renderDiagnosticJson(d, raw)));
  EXPECT_EQ(j.value("code", ""), "E0105");
}

}  // namespace
}  // namespace cbtl
