// Every golden program that compiles, and every domain: emit JSON -> read -> emit JSON gives the same bytes.
// The JSON carries every field of the graph (GraphPrinter.h), so equal bytes mean the read graph equals the
// compiled one.
#include "compiler/driver/Pipeline.h"
#include "ir/GraphJsonReader.h"
#include "ir/GraphPrinter.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> programs() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(CBTL_GOLDEN_DIR)) {
    if (entry.is_regular_file() && entry.path().extension() == ".cbtl") out.push_back(entry.path());
  }
  for (const char* d : {"cooking", "cleaning", "books", "feeding"})
    out.push_back(fs::path(CBTL_DOMAINS_DIR) / d / (std::string(d) + ".cbtl"));
  std::sort(out.begin(), out.end());
  return out;
}

// The `--stdlib DIR` of a golden case's `// ARGS:` line, relative to the case's folder.
std::string stdlibOf(const fs::path& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  std::smatch m;
  if (std::regex_search(first, m, std::regex("^// ARGS:.*--stdlib +(\\S+)")))
    return (file.parent_path() / m[1].str()).string();
  return "";
}

TEST(GraphJsonRoundTrip, EveryCompilingProgramReadsBackToTheSameBytes) {
  std::size_t compiled = 0;
  for (const auto& file : programs()) {
    CompileOptions options;
    options.stdlibDir = stdlibOf(file);
    TranslationUnit tu(options);
    if (compileFile(tu, file.string()).outcome != PipelineOutcome::Ok) continue;
    ++compiled;
    const std::string first = ir::toJson(tu.graph);
    const ir::GraphReadResult read = ir::readGraphJson(first);
    ASSERT_TRUE(read.ok()) << read.describe(file.string());
    EXPECT_EQ(ir::toJson(read.graph), first) << file;
    EXPECT_EQ(ir::toText(read.graph), ir::toText(tu.graph)) << file;
  }
  EXPECT_GE(compiled, 40u);  // the goldens hold many programs that compile; a broken walk must not pass
}

}  // namespace
}  // namespace cbtl
