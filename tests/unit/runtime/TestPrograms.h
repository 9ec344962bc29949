// TestPrograms.h — small .cbtl programs the runtime tests compile in memory.
#pragma once

#include "app/LoadedProgram.h"

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace cbtl::test {

// The reference solver test's CSP: x < y, plus a learned constraint "y small" (a threshold model on y).
inline const char* kTinySource = R"(domain tiny;
var x : real in 0 .. 10 = 0;
var y : real in 0 .. 10 = 0;
var n : int in 0 .. 10 = 0;
require order: x < y;
sample x ~ uniform;
sample y ~ uniform;
sample n ~ uniform;
feedback rated(v: real, good: bool);
personal smallY(v: real) {
  when v ~ "y";
  model threshold(v, 0 .. 10, below);
  learn rated(v, good) => good;
}
)";

inline std::unique_ptr<app::LoadedProgram> compileOrFail(const std::string& name, const std::string& text) {
  auto lp = app::LoadedProgram::fromSource(name, text);
  EXPECT_TRUE(lp->ok()) << lp->errors();
  return lp;
}

inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string cookingPath() { return std::string(CBTL_DOMAINS_DIR) + "/cooking/cooking.cbtl"; }

}  // namespace cbtl::test
