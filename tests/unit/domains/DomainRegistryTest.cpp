// The registry creates simulators by domain name and knows nothing else.
#include "domains/DomainRegistry.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using cbtl::domains::createSimulator;
using cbtl::domains::knownDomains;

TEST(DomainRegistry, KnowsCooking) {
  const auto names = knownDomains();
  EXPECT_NE(std::find(names.begin(), names.end(), "cooking"), names.end());
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
}

TEST(DomainRegistry, CreatesCookingSimulatorSeeded) {
  auto a = createSimulator("cooking", {}, {}, 7);
  auto b = createSimulator("cooking", {}, {}, 7);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  const auto obs = a->observe();
  ASSERT_EQ(obs.count("stock[salt]"), 1u);
  EXPECT_EQ(obs.at("stock[salt]").number, b->observe().at("stock[salt]").number);
}

TEST(DomainRegistry, UnknownDomainIsNull) {
  EXPECT_EQ(createSimulator("no-such-domain", {}, {}, 1), nullptr);
  EXPECT_EQ(createSimulator("", {}, {}, 1), nullptr);
}

}  // namespace
