// Every scenario in bench/scenarios/, bench/heldout/ and bench/unseen/ loads, its queries are
// collision-free at both ends, and a witness path, when given, is collision-free at a quarter of the
// checking resolution. The directories are read at run time, so files added later are covered
// without touching this test.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "cspace/certified_motion_validator.hpp"
#include "cspace/collision_checker.hpp"
#include "cspace/scenario/scenario.hpp"

namespace svmp::cspace {
namespace {

std::vector<std::filesystem::path> scenarioFiles() {
  std::vector<std::filesystem::path> files;
  for (const char* dir : {"/bench/scenarios", "/bench/heldout", "/bench/unseen"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(SVMP_SOURCE_DIR) + dir))
      if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ScenarioFilesTest, EveryFileLoadsAndItsWitnessIsFree) {
  const auto files = scenarioFiles();
  ASSERT_FALSE(files.empty());
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    Scenario s;
    try {
      s = loadScenario(file.string());
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    const CollisionChecker checker(s.robot, s.environment, s.self_collision);
    const ConfigurationSpace space = s.makeSpace();
    const CertifiedMotionValidator certified(checker, space, s.resolution);
    ASSERT_FALSE(s.queries.empty());
    for (size_t i = 0; i < s.queries.size(); ++i) {
      const Query& query = s.queries[i];
      EXPECT_EQ(checker.check(query.start), kFree) << "query " << i << " start";
      EXPECT_EQ(checker.check(query.goal), kFree) << "query " << i << " goal";
      const std::vector<Eigen::VectorXd> path = query.witnessPath();
      for (size_t k = 0; k + 1 < path.size(); ++k)
        EXPECT_TRUE(certified.isValid(path[k], path[k + 1]))
            << "query " << i << ": witness segment " << k << " [" << path[k].transpose() << "] -> ["
            << path[k + 1].transpose() << "] is not certified free";
    }
  }
}

}  // namespace
}  // namespace svmp::cspace
