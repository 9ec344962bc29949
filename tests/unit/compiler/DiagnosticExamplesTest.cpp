// `cbtlc explain`'s examples are real: for every code, the wrong program reports it and the right one compiles
// with no diagnostic at all (the files are written to a temporary folder, so imports resolve as for a user).
#include "compiler/diag/DiagnosticCodes.h"
#include "compiler/diag/DiagnosticExamples.h"
#include "compiler/driver/Pipeline.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

struct Compiled {
  std::vector<std::string> codes;  // of every diagnostic, in order
};

Compiled compileExample(std::string_view text, std::string_view importedName, std::string_view importedText,
                        const std::string& tag) {
  const fs::path dir = fs::temp_directory_path() / ("cbtl-example-" + tag + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "example.cbtl") << text;
  if (!importedName.empty() && !importedText.empty()) std::ofstream(dir / std::string(importedName)) << importedText;
  TranslationUnit tu{CompileOptions{}};
  compileFile(tu, (dir / "example.cbtl").string());
  Compiled c;
  for (const auto& d : tu.diags.sorted()) c.codes.push_back(d.code);
  fs::remove_all(dir);
  return c;
}

TEST(DiagnosticExamples, EveryCodeHasOneExceptTheInternalOne) {
  for (const auto& info : diagnosticCodes()) {
    if (info.code == "E0901") {
      EXPECT_EQ(exampleFor(info.code), nullptr);
      continue;
    }
    EXPECT_NE(exampleFor(info.code), nullptr) << info.code << " has no wrong/right example";
  }
  for (const auto& e : diagnosticExamples())
    EXPECT_NE(findDiagnosticCode(std::string(e.code)), nullptr) << "an example for the unknown code " << e.code;
}

TEST(DiagnosticExamples, TheWrongProgramReportsItsCodeAndTheRightOneCompilesCleanly) {
  for (const auto& e : diagnosticExamples()) {
    const std::string code(e.code);
    const Compiled wrong = compileExample(e.wrong, e.imported, e.importedWrong, code + "-wrong");
    EXPECT_NE(std::find(wrong.codes.begin(), wrong.codes.end(), code), wrong.codes.end())
        << code << ": the wrong example does not report it";
    const Compiled right = compileExample(e.right, e.imported, e.importedRight, code + "-right");
    EXPECT_TRUE(right.codes.empty()) << code << ": the right example reports " << right.codes.front();
  }
}

}  // namespace
}  // namespace cbtl
