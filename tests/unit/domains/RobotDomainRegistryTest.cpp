// The registry's robot domains: created from their program's facts, a clear error without a scene.
#include "domains/DomainRegistry.h"

#include "tests/unit/domains/ProgramFactsSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace {

TEST(DomainRegistry, CreatesTheHomeDomainsButNotTheRobotLibrary) {
  const auto names = cbtl::domains::knownDomains();
  for (const char* home : {"books", "cleaning"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), home), names.end()) << home;
    EXPECT_NE(cbtl::domains::createSimulator(home, cbtl::test::programFacts(home), {}, 3), nullptr) << home;
  }
  EXPECT_EQ(std::find(names.begin(), names.end(), "robot"), names.end());
}

TEST(DomainRegistry, ARobotDomainWithoutASceneIsAClearError) {
  for (const char* robot : {"books", "cleaning", "feeding"}) {
    try {
      cbtl::domains::createSimulator(robot, {}, {}, 1);
      ADD_FAILURE() << robot << " was created without a scene";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("no scene"), std::string::npos) << e.what();
    }
  }
}

TEST(DomainRegistry, ASceneGivenOnlyByItsPathIsLoaded) {
  cbtl::domains::ProgramFacts facts;
  facts.scenePath = std::string(CBTL_DOMAINS_DIR) + "/home/home.xml";
  auto fromPath = cbtl::domains::createSimulator("cleaning", facts, {}, 3);
  auto shared = cbtl::domains::createSimulator("cleaning", cbtl::test::programFacts("cleaning"), {}, 3);
  ASSERT_NE(fromPath, nullptr);
  ASSERT_NE(shared, nullptr);
  EXPECT_EQ(fromPath->observe().at("clearSurfaces").members, shared->observe().at("clearSurfaces").members);
  facts.scenePath = std::string(CBTL_DOMAINS_DIR) + "/home/no-such-scene.xml";
  EXPECT_THROW(cbtl::domains::createSimulator("cleaning", facts, {}, 3), std::runtime_error);
}

}  // namespace
