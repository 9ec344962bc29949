// formatSource: the canonical layout of .cbtl files (compiler/format/SourceFormatter.h).
#include "compiler/format/SourceFormatter.h"

#include "compiler/parse/Parser.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every domain and standard-library file of the repository.
std::vector<fs::path> repositorySources() {
  const fs::path root = fs::path(CBTL_GOLDEN_DIR).parent_path().parent_path();
  std::vector<fs::path> files;
  for (const char* dir : {"domains", "stdlib/std"})
    for (const auto& e : fs::recursive_directory_iterator(root / dir))
      if (e.path().extension() == ".cbtl") files.push_back(e.path());
  return files;
}

TEST(SourceFormatter, IndentsByBlockAndSpacesTokens) {
  const std::string messy =
      "domain   d;\n"
      "var x:real in 0 ..1;\n"
      "    require  ok : x<=0.5 and(x>=0.1);\n"
      "skill s( p :real ){\n"
      "var y : real in 0 .. 1 ;\n"
      "      require near: abs( y-p )<=0.1 ;\n"
      "   }\n";
  const std::string expected =
      "domain d;\n"
      "var x: real in 0 .. 1;\n"
      "require ok : x <= 0.5 and (x >= 0.1);\n"
      "skill s(p : real) {\n"
      "  var y : real in 0 .. 1;\n"
      "  require near: abs(y - p) <= 0.1;\n"
      "}\n";
  EXPECT_EQ(formatSource(messy), expected);
  EXPECT_EQ(formatSource(expected), expected);
}

TEST(SourceFormatter, SpacesOperatorsByTheirRoleInTheParse) {
  EXPECT_EQ(formatSource("var v : vec < 2 > in [ - 1 .. 1,0 ..1 ];\nrequire r: v.x<v.y and - v.x>-1*v.y;\n"),
            "var v : vec<2> in [-1 .. 1, 0 .. 1];\nrequire r: v.x < v.y and -v.x > -1 * v.y;\n");
  EXPECT_EQ(formatSource("extern sampler box < N > (lo : vec< N >) -> vec <N>;\n"),
            "extern sampler box<N>(lo : vec<N>) -> vec<N>;\n");
}

TEST(SourceFormatter, LengthsAndAllowBlocks) {
  const std::string messy =
      "clearance person:\"user\",\"user_head\">=5cm;\n"
      "clearance far: \"table\",\n"
      "\"shelf\" >= - 1  m;\n"
      "skill s {\n"
      "do {\n"
      "allow held near person 5mm{\n"
      "allow gripper touch \"table_top\" 0.5 cm { say(\"x\") ; }\n"
      "}\n"
      "}\n"
      "}\n";
  const std::string expected =
      "clearance person: \"user\", \"user_head\" >= 5 cm;\n"
      "clearance far: \"table\",\n"
      "    \"shelf\" >= -1 m;\n"
      "skill s {\n"
      "  do {\n"
      "    allow held near person 5 mm {\n"
      "      allow gripper touch \"table_top\" 0.5 cm { say(\"x\"); }\n"
      "    }\n"
      "  }\n"
      "}\n";
  EXPECT_EQ(formatSource(messy), expected);
  EXPECT_EQ(formatSource(expected), expected);
}

TEST(SourceFormatter, KeepsAlignmentAndMovesContinuationsWithTheirStatement) {
  const std::string text =
      "const a = 1;        // one\n"
      "const bb = 22;      // two\n"
      "                    // still two\n"
      "fn f(x: real) -> real =\n"
      "    x + a\n"
      "      + bb;\n"
      "items e : E {\n"
      "  first  { n: 1 },\n"
      "  second { n: 2 },\n"
      "}\n";
  EXPECT_EQ(formatSource(text), text);
  // The same file indented by three more spaces everywhere: statements go back to their indentation and take
  // their continuation lines (and aligned comments) with them.
  std::string shifted;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) shifted += "   " + line + "  \n";
  EXPECT_EQ(formatSource(shifted), text);
}

TEST(SourceFormatter, BlankLinesCommentsAndLineEnds) {
  EXPECT_EQ(formatSource("\n\n// c\r\n\r\n\r\n\r\ndomain d;\t// t\r\n\n\n"), "// c\n\ndomain d; // t\n");
  EXPECT_EQ(formatSource(""), "");
  EXPECT_EQ(formatSource("   \n\t\n"), "");
  // A block comment spanning lines is kept as it is, and the code after it stays on its line.
  const std::string block = "/* one\n     two */ domain d;\n";
  EXPECT_EQ(formatSource(block), block);
  // Columns count code points: an aligned comment after a UTF-8 comment stays aligned.
  const std::string utf8 = "const a = 1;  // é — ok\nconst b = 2;  // plain\n";
  EXPECT_EQ(formatSource(utf8), utf8);
}

TEST(SourceFormatter, EveryRepositoryFileIsAlreadyFormatted) {
  const auto files = repositorySources();
  ASSERT_GE(files.size(), 12u);
  for (const auto& p : files) {
    const std::string text = readText(p);
    EXPECT_EQ(formatSource(text), text) << p;
  }
}

// Messing up what the layout rules decide (indentation of the whole file, spaces inside brackets and before
// separators, trailing spaces, extra blank lines) and formatting gives back the file.
TEST(SourceFormatter, UndoesLayoutNoiseOnEveryRepositoryFile) {
  for (const auto& p : repositorySources()) {
    const std::string text = readText(p);
    std::string noisy;
    std::istringstream in(text);
    int n = 0;
    for (std::string line; std::getline(in, line); ++n) {
      if (line.empty()) {
        noisy += "\n \n\n";  // more blank lines, one with a space
        continue;
      }
      std::string l = line;
      if (l.find("//") == std::string::npos && l.find('"') == std::string::npos) {
        std::string spaced;
        for (char c : l) {
          if (c == '(')
            spaced += "( ";
          else if (c == ')' || c == ';' || c == ',')
            spaced += std::string(" ") + c;
          else
            spaced += c;
        }
        l = spaced;
      }
      noisy += (n % 2 == 0 ? "\t " : "  ") + l + "   \n";  // every line two columns in (a tab counts as one)
    }
    const std::string formatted = formatSource(noisy);
    EXPECT_EQ(formatted, text) << p;
    EXPECT_EQ(formatSource(formatted), formatted) << p << ": not idempotent";
  }
}

// Byte offsets of the whitespace outside comments and strings: where layout can change without changing tokens.
std::vector<std::size_t> layoutPositions(const std::string& text) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text.compare(i, 2, "//") == 0) {
      i = text.find('\n', i);
      if (i == std::string::npos) break;
    } else if (text.compare(i, 2, "/*") == 0) {
      i = text.find("*/", i + 2);
      if (i == std::string::npos) break;
      ++i;
    } else if (text[i] == '"') {
      for (++i; i < text.size() && text[i] != '"' && text[i] != '\n'; ++i)
        if (text[i] == '\\') ++i;
    } else if (text[i] == ' ' || text[i] == '\n') {
      out.push_back(i);
    }
  }
  return out;
}

// Line breaks, indentation and spaces inserted at random between tokens of every repository file and golden input
// that parses: the formatter keeps the tokens (it checks that itself, throwing if not) and its output is a fixed
// point.
TEST(SourceFormatter, RandomLayoutsFormatToAFixedPoint) {
  std::vector<fs::path> files = repositorySources();
  for (const auto& e : fs::recursive_directory_iterator(CBTL_GOLDEN_DIR))
    if (e.path().extension() == ".cbtl") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::mt19937_64 rng(20261205);
  const std::vector<std::string> inserts = {" ", "  ", "\n", "\n    ", "\n\n", "\t", "      "};
  int checked = 0;
  for (const auto& p : files) {
    const std::string text = readText(p);
    SourceManager sources;
    DiagnosticEngine diags;
    if (parseModule(sources, sources.add(p.string(), text), diags).hadSyntaxErrors) continue;  // layout needs syntax
    const auto positions = layoutPositions(text);
    if (positions.empty()) continue;
    for (int round = 0; round < 5; ++round) {
      std::vector<std::size_t> picks;
      for (int k = 0; k < 12; ++k) picks.push_back(positions[rng() % positions.size()]);
      std::sort(picks.begin(), picks.end(), std::greater<>());
      std::string mutated = text;
      for (std::size_t at : picks) mutated.insert(at, inserts[rng() % inserts.size()]);
      std::string once;
      ASSERT_NO_THROW(once = formatSource(mutated)) << p << " round " << round;
      EXPECT_EQ(formatSource(once), once) << p << " round " << round << ": not idempotent";
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

}  // namespace
}  // namespace cbtl
