// Every `extern fn` and `extern sampler` the standard library declares has a runtime binding, and std.text's
// built-ins compute what their declarations promise when called from a compiled program.
#include "tests/unit/runtime/TestPrograms.h"

#include "robot/bind/WorldBuiltins.h"
#include "runtime/core/Builtins.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

using namespace cbtl;

namespace {

struct ExternDecl {
  std::string file, kind, name;  // kind: fn | sampler
};

// The extern functions and samplers declared in stdlib/std/*.cbtl (declarations start a line; generic ones are
// spelled `name<N>(`). Actions are bound by the domain simulators, not here.
std::vector<ExternDecl> stdlibExterns() {
  std::vector<ExternDecl> out;
  const std::regex decl(R"(^\s*extern\s+(fn|sampler)\s+([A-Za-z_][A-Za-z0-9_]*))");
  for (const auto& entry : std::filesystem::directory_iterator(CBTL_STDLIB_DIR)) {
    if (entry.path().extension() != ".cbtl") continue;
    std::ifstream in(entry.path());
    std::string line;
    std::smatch m;
    while (std::getline(in, line)) {
      if (std::regex_search(line, m, decl)) out.push_back({entry.path().filename().string(), m[1], m[2]});
    }
  }
  return out;
}

rt::Builtins everyRegistry() {
  rt::Builtins b = rt::Builtins::standard();
  std::string error;
  EXPECT_TRUE(bind::addWorldFromFile(b, std::string(CBTL_DOMAINS_DIR) + "/feeding/feeding.xml", error)) << error;
  return b;
}

// Evaluates constraint `i` of a program without variables.
bool holds(const app::LoadedProgram& lp, std::size_t i) {
  const auto& program = lp.program();
  std::vector<double> x(program.assignmentWidth() + 1), frame(64), obs(program.observationWidth() + 1);
  rt::EvalContext ctx{x.data(), obs.data(), frame.data(), program.callContext()};
  return program.pool().evalBool(program.constraints().at(i).root, ctx);
}

}  // namespace

TEST(StdlibBinding, EveryExternHasABinding) {
  const auto externs = stdlibExterns();
  ASSERT_GE(externs.size(), 50u) << "the stdlib scan found too few declarations: " << CBTL_STDLIB_DIR;
  const rt::Builtins b = everyRegistry();
  for (const auto& e : externs) {
    if (e.kind == "fn")
      EXPECT_NE(b.function(e.name), nullptr) << e.file << ": extern fn " << e.name << " has no binding";
    else
      EXPECT_NE(b.sampler(e.name), nullptr) << e.file << ": extern sampler " << e.name << " has no binding";
  }
}

TEST(StdlibBinding, WorldNamesListWhatWithWorldAdds) {
  const auto standard = rt::Builtins::standard();
  const auto all = everyRegistry();
  std::set<std::string> added;
  for (const auto& n : all.functionNames()) {
    if (standard.function(n) == nullptr) added.insert(n);
  }
  for (const auto& n : all.samplerNames()) {
    if (standard.sampler(n) == nullptr) added.insert(n);
  }
  const auto names = bind::worldBuiltinNames();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), added);
}

TEST(StdlibBinding, TextBuiltinsFromACompiledProgram) {
  auto lp = test::compileOrFail("t.cbtl", R"(domain t;
import std.text;
require containsText("I Can't REACH it", "can't reach");
require not containsText("salt", "pepper");
require containsText("abc", "");
require lowercase("SaLT and Pepper") == "salt and pepper";
require lowercase("Crème") + "!" == "crème!";
require textLength("") == 0;
require textLength("salt") == 4;
require textLength("crème") == 5;
require textLength(lowercase("ABC")) == 3;
)");
  ASSERT_TRUE(lp->ok()) << lp->errors();
  ASSERT_EQ(lp->program().constraints().size(), 9u);
  for (std::size_t i = 0; i < 9; ++i) EXPECT_TRUE(holds(*lp, i)) << "constraint " << i + 1;
}

TEST(StdlibBinding, TextBuiltinsAreFalseWhereTheyShouldBe) {
  auto lp = test::compileOrFail("f.cbtl", R"(domain f;
import std.text;
require containsText("salt", "salty");
require lowercase("ABC") == "ABC";
require textLength("crème") == 6;
)");
  ASSERT_TRUE(lp->ok()) << lp->errors();
  for (std::size_t i = 0; i < 3; ++i) EXPECT_FALSE(holds(*lp, i)) << "constraint " << i + 1;
}

// The widths a built-in reads and writes match its declaration: each non-generic extern of the language-level
// modules is called with exactly its declared argument widths (text arguments a valid string id, everything
// else 0.5) followed by NaN padding, and an output of its declared result width followed by a sentinel. A
// built-in that reads past its arguments gets NaN into its result; one that writes past its result changes
// the sentinel. (The world built-ins need a scene and are bound and exercised in WorldBindingTest.)
TEST(StdlibBinding, BuiltinsReadAndWriteTheirDeclaredWidths) {
  auto lp = test::compileOrFail("w.cbtl", "domain w;\nimport std.prelude;\nimport std.geometry;\nimport std.text;\n");
  ASSERT_TRUE(lp->ok()) << lp->errors();
  const auto& program = lp->program();
  const rt::Builtins b = rt::Builtins::standard();
  const rt::CallContext& cx = *program.callContext();
  const double textId = cx.strings->intern("Salt");
  constexpr double kSentinel = 12345.678;
  std::size_t checked = 0;
  for (const auto& f : lp->graph().functions) {
    if (!f.isExtern || f.kind == ir::FunctionKind::Action || !f.typeParams.empty()) continue;
    std::vector<double> args;
    std::vector<std::uint16_t> widths;
    for (const auto& p : f.params) {
      const rt::ValueType t = program.typeOf(p.type);
      widths.push_back(static_cast<std::uint16_t>(t.width));
      args.insert(args.end(), t.width, t.kind == rt::ValueKind::Text ? textId : 0.5);
    }
    const std::size_t argWidth = args.size();
    args.resize(argWidth + 8, std::nan(""));
    const std::size_t resultWidth = program.typeOf(f.result).width;
    std::vector<double> out(resultWidth + 8, kSentinel);
    bool produced = true;
    if (f.kind == ir::FunctionKind::Sampler) {
      const auto impl = b.sampler(f.name);
      ASSERT_NE(impl, nullptr) << f.name;
      rt::Rng rng(1);
      produced = impl(cx, std::span(args.data(), argWidth), widths, rng, std::span(out.data(), resultWidth));
    } else {
      const auto impl = b.function(f.name);
      ASSERT_NE(impl, nullptr) << f.name;
      impl(cx, std::span(args.data(), argWidth), widths, std::span(out.data(), resultWidth));
    }
    for (std::size_t i = resultWidth; i < out.size(); ++i)
      EXPECT_EQ(out[i], kSentinel) << f.name << " wrote past its result";
    if (produced) {
      for (std::size_t i = 0; i < resultWidth; ++i) EXPECT_FALSE(std::isnan(out[i])) << f.name << " result " << i;
    }
    ++checked;
  }
  EXPECT_GE(checked, 30u);
}

// keepOrUniformInBox keeps its first argument with probability pKeep when it lies in the box, and otherwise draws
// a point of the box; the same draws are made whichever way it chooses.
TEST(StdlibBinding, KeepOrUniformInBoxKeepsTheValueAsOftenAsAsked) {
  const rt::Builtins b = rt::Builtins::standard();
  const auto impl = b.sampler("keepOrUniformInBox");
  ASSERT_NE(impl, nullptr);
  const rt::CallContext cx{};
  const std::vector<std::uint16_t> widths{2, 2, 2, 1};
  const auto draw = [&](std::vector<double> args, rt::Rng& rng, std::vector<double>& out) {
    out.assign(2, std::nan(""));
    return impl(cx, std::span(args.data(), args.size()), widths, rng, std::span(out.data(), out.size()));
  };
  std::vector<double> out;
  int kept = 0, inBox = 0;
  rt::Rng rng(7);
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(draw({0.34, 0.45, 0.30, 0.25, 0.38, 0.64, 0.5}, rng, out));
    if (out[0] == 0.34 && out[1] == 0.45) ++kept;
    if (out[0] >= 0.30 && out[0] <= 0.38 && out[1] >= 0.25 && out[1] <= 0.64) ++inBox;
  }
  EXPECT_EQ(inBox, 2000);
  EXPECT_GT(kept, 900);
  EXPECT_LT(kept, 1100);

  rt::Rng always(3);
  ASSERT_TRUE(draw({0.34, 0.45, 0.30, 0.25, 0.38, 0.64, 1.0}, always, out));
  EXPECT_EQ(out, (std::vector<double>{0.34, 0.45}));
  // A value outside the box is never kept.
  rt::Rng outside(3);
  ASSERT_TRUE(draw({0.50, 0.45, 0.30, 0.25, 0.38, 0.64, 1.0}, outside, out));
  EXPECT_LE(out[0], 0.38);
  // pKeep 0 draws exactly what it draws with pKeep 1 for a value outside the box: the stream does not branch.
  rt::Rng never(3);
  std::vector<double> drawn;
  ASSERT_TRUE(draw({0.34, 0.45, 0.30, 0.25, 0.38, 0.64, 0.0}, never, drawn));
  EXPECT_EQ(drawn, out);
  rt::Rng bad(3);
  EXPECT_FALSE(draw({0.34, 0.45, 0.30, 0.25, 0.38, 0.64, 1.5}, bad, out));
  EXPECT_FALSE(draw({0.34, 0.45, 0.38, 0.25, 0.30, 0.64, 0.5}, bad, out));
}
