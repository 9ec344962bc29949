// The limits of compiler/driver/CompileLimits.h on inputs too large for a golden file: each must end in its located
// diagnostic, not in a crash or an exhausted machine. (The small hostile programs are golden cases:
// types/inlining_explosion, types/call_depth, lowering/quantifier_nest, generators/too_many_instances,
// generators/instance_search.)
#include "compiler/driver/CompileLimits.h"
#include "compiler/driver/Pipeline.h"

#include <gtest/gtest.h>

#include <string>

namespace cbtl {
namespace {

// The codes reported for `text`, in source order.
std::vector<std::string> codesOf(const std::string& text) {
  TranslationUnit tu(CompileOptions{});
  compileSource(tu, "limits.cbtl", text);
  std::vector<std::string> codes;
  for (const auto& d : tu.diags.sorted()) codes.push_back(d.code);
  return codes;
}

// A chain of 40,000 functions, each calling the next (1.5 MB): the recursion check used to follow it with one
// stack frame per function and overflowed the stack (SIGSEGV). Now the walk keeps its own stack, and the chain is
// E0319 (calls nested more than kMaxCallDepth deep) at the one function where the depth first exceeds the limit.
TEST(CompileLimits, ALongChainOfFunctionsIsOneErrorNotAStackOverflow) {
  constexpr int kFunctions = 40000;
  std::string text = "var x : real in 0 .. 1;\nsample x ~ uniform;\n";
  for (int k = 0; k < kFunctions; ++k)
    text += "fn f" + std::to_string(k) + "(v: real) -> real = f" + std::to_string(k + 1) + "(v);\n";
  text += "fn f" + std::to_string(kFunctions) + "(v: real) -> real = v;\nrequire f0(x) > 0;\n";
  EXPECT_EQ(codesOf(text), std::vector<std::string>{"E0319"});
}

// A chain exactly as deep as the runtime allows compiles: calling f0 inlines f0 .. f63, 64 nested calls.
TEST(CompileLimits, CallsNestedAsDeepAsTheLimitCompile) {
  const auto depth = static_cast<int>(CompileLimits::kMaxCallDepth) - 1;
  std::string text = "var x : real in 0 .. 1;\nsample x ~ uniform;\n";
  for (int k = 0; k < depth; ++k)
    text += "fn f" + std::to_string(k) + "(v: real) -> real = f" + std::to_string(k + 1) + "(v);\n";
  text += "fn f" + std::to_string(depth) + "(v: real) -> real = v;\nrequire f0(x) > 0;\n";
  EXPECT_TRUE(codesOf(text).empty());
}

}  // namespace
}  // namespace cbtl
