// What the driver writes: the JSON of results and of paths parse back (yaml-cpp reads JSON) with the
// same numbers and waypoints, a scenario name with quotes stays valid JSON, OMPL matrix files hold one
// configuration a line, a hostile name cannot write outside the output directory, and planners take
// turns seed by seed.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/experiments/experiment.hpp"
#include "bench/experiments/output_text.hpp"
#include "bench/experiments/run_records.hpp"
#include "bench/experiments/scenario_check.hpp"
#include "cspace/collision_checker.hpp"

namespace svmp::experiments {
namespace {

namespace fs = std::filesystem;

struct Experiment {
  cspace::Scenario scenario;
  DriverOptions options;
  std::vector<PlannerRuns> results;
  std::string log;
};

// One planner on a scenario given as text.
Experiment runText(const std::string& yaml, const std::string& planner, int runs, double time_limit = 0) {
  Experiment run{cspace::parseScenario(yaml, "inline.yaml"), {}, {}, {}};
  run.options.planners = {planner};
  run.options.runs = runs;
  run.options.time_limit = time_limit;
  std::ostringstream log;
  run.results = runExperiment(run.scenario, run.options, log);
  run.log = log.str();
  return run;
}

Experiment runFig35(const std::string& name) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig3_5.yaml";
  Experiment run{cspace::loadScenario(path), {}, {}, {}};
  run.scenario.name = name;
  run.options.scenario = path;
  run.options.planners = {"svmp", "prm"};
  run.options.runs = 3;
  run.options.simplify = true;
  std::ostringstream log;
  run.results = runExperiment(run.scenario, run.options, log);
  return run;
}

TEST(DriverOutput, PathsAndResultsParseBackWithTheSameValues) {
  const Experiment run = runFig35("fig \"3.5\" \\ test");
  const fs::path dir = fs::temp_directory_path() / "svmp_driver_output_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  writeJson((dir / "r.json").string(), run.scenario, run.options, run.results);
  writePathsJson((dir / "p.json").string(), run.scenario, run.results);
  std::ostringstream log;
  writePathMatrices(dir.string(), run.scenario, run.results, log);

  const YAML::Node results = YAML::LoadFile((dir / "r.json").string());
  EXPECT_EQ(results["scenario"].as<std::string>(), run.scenario.name);
  ASSERT_EQ(results["results"].size(), 2u);
  EXPECT_EQ(results["results"][0]["solved"].as<int>(), run.results[0].solved());
  EXPECT_EQ(results["results"][0]["certified"].as<int>(), run.results[0].certified());
  EXPECT_EQ(results["results"][0]["solved"].as<int>(), results["results"][0]["certified"].as<int>());

  const YAML::Node paths = YAML::LoadFile((dir / "p.json").string());
  ASSERT_EQ(paths["runs"].size(), 6u);
  int matrices = 0;
  for (size_t p = 0, n = 0; p < run.results.size(); ++p)
    for (const auto& r : run.results[p].runs) {
      const YAML::Node node = paths["runs"][n++];
      EXPECT_EQ(node["planner"].as<std::string>(), run.results[p].planner);
      EXPECT_EQ(node["seed"].as<std::uint64_t>(), r.seed);
      ASSERT_EQ(node["path"].size(), r.result.solved() ? r.result.path.size() : 0u);
      for (size_t i = 0; i < node["path"].size(); ++i)
        for (int d = 0; d < r.result.path[i].size(); ++d)
          EXPECT_EQ(node["path"][i][d].as<double>(), r.result.path[i][d]);  // 17 digits: exact
      if (!r.result.solved()) continue;
      // The matrix file: one line per waypoint, dof numbers each.
      ++matrices;
      const fs::path file = dir / (safeFileName(run.scenario.name + "_" + run.results[p].planner + "_seed" +
                                                std::to_string(r.seed)) + ".txt");
      std::ifstream in(file);
      ASSERT_TRUE(in) << file;
      size_t lines = 0;
      for (std::string line; std::getline(in, line); ++lines) {
        std::istringstream values(line);
        double x, y;
        ASSERT_TRUE(values >> x >> y);
        EXPECT_EQ(x, r.result.path[lines][0]);
        EXPECT_EQ(y, r.result.path[lines][1]);
      }
      EXPECT_EQ(lines, r.result.path.size());
    }
  EXPECT_GT(matrices, 0);
  // Simplification never lengthens a path.
  for (const auto& runs : run.results)
    for (const auto& r : runs.runs)
      if (r.result.solved()) {
        EXPECT_LE(r.path_length, r.raw_length + 1e-12);
      }
  fs::remove_all(dir);
}

// The JSON says what ran and where: the code's revision, the machine, and each planner's parameters
// as it used them, those it derived from the problem included (svmp's step is 1/40 of the mean
// side, sigma twice the step).
TEST(DriverOutput, TheJsonSaysWhatRanAndWhereItRan) {
  const Experiment run = runText(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [4, 2]}}\n"
      "obstacles: [{name: a, shape: box, size: [0.4, 0.4, 1], position: [1, 1, 0]},\n"
      "            {name: b, shape: box, size: [0.4, 0.4, 1], position: [3, 1, 0]}]\n"
      "start: [0.2, 0.2]\ngoal: [3.8, 1.8]\nresolution: 0.01\nplanners: {svmp: {k: 7}}\n",
      "svmp", 1);
  const fs::path file = fs::temp_directory_path() / "svmp_driver_provenance_test.json";
  writeJson(file.string(), run.scenario, run.options, run.results);
  const YAML::Node json = YAML::LoadFile(file.string());
  fs::remove(file);
  EXPECT_EQ(json["revision"].as<std::string>(), sourceRevision());
  EXPECT_FALSE(json["revision"].as<std::string>().empty());
  EXPECT_FALSE(json["version"].as<std::string>().empty());
  EXPECT_FALSE(json["host"].as<std::string>().empty());
  EXPECT_NE(json["cpu"].as<std::string>().find("logical processors"), std::string::npos);
  const std::string simd = json["simd"].as<std::string>();
  EXPECT_TRUE(simd == "avx512" || simd == "avx2" || simd == "sse2") << simd;
  const YAML::Node params = json["results"][0]["parameters"];
  EXPECT_EQ(params["k"].as<int>(), 7);                   // set in the file
  EXPECT_EQ(params["repair_rounds"].as<int>(), 5);       // its default
  EXPECT_DOUBLE_EQ(params["step"].as<double>(), 0.075);  // derived: (4 + 2) / 2 / 40
  EXPECT_DOUBLE_EQ(params["sigma"].as<double>(), 0.15);
}

// An obstacle SVMP has no sample of is told: in the run's warnings, once in the log, and in the JSON.
TEST(DriverOutput, ObstaclesLeftUnsampledAreWarnedAbout) {
  const Experiment run = runText(
      "robot: {type: planar_arm, lengths: [1.0, 0.8], widths: 0.05, limits: {lower: [-pi, -2.5], upper: [pi, 2.5]}}\n"
      "obstacles:\n"
      "  - {name: near, shape: box, size: [0.2, 0.2, 1], position: [0.6, 0.6, 0]}\n"
      "  - {name: rim, shape: box, size: [0.2, 0.2, 1], position: [1.4, -0.4, 0]}\n"
      "  - {name: far, shape: box, size: [0.2, 0.2, 1], position: [2.5, 0, 0]}\n"
      "start: [0, 0]\ngoal: [2.5, 0]\nresolution: 0.01\n",
      "svmp", 2);
  ASSERT_EQ(run.results[0].runs.size(), 2u);
  for (const auto& r : run.results[0].runs) {
    ASSERT_EQ(r.result.warnings.size(), 1u) << planners::planStatusName(r.result.status);
    EXPECT_NE(r.result.warnings[0].find("'far': beyond the robot's reach"), std::string::npos) << r.result.warnings[0];
  }
  const std::string& text = run.log;
  const size_t first = text.find("svmp warning: obstacle 'far'");
  ASSERT_NE(first, std::string::npos) << text;
  EXPECT_EQ(text.find("svmp warning:", first + 1), std::string::npos) << "warned more than once:\n" << text;
  const fs::path file = fs::temp_directory_path() / "svmp_driver_warnings_test.json";
  writeJson(file.string(), run.scenario, run.options, run.results);
  const YAML::Node records = YAML::LoadFile(file.string())["results"][0]["records"];
  EXPECT_EQ(records[1]["warnings"][0].as<std::string>(), run.results[0].runs[1].result.warnings[0]);
  fs::remove(file);
}

// A warning first raised on a later seed reaches the log too, once, with its seed (only the first
// run's were logged): a grain the root search misses on seed 2 and finds on seeds 1 and 3.
TEST(DriverOutput, AWarningOfALaterSeedIsLoggedWithItsSeed) {
  const Experiment run = runText(
      "robot: {type: planar_arm, lengths: [1.0, 1.0], widths: 0.0002}\n"
      "obstacles:\n"
      "  - {name: wall, shape: box, size: [0.2, 0.6, 1.0], position: [0, 1.6, 0]}\n"
      "  - {name: grain, shape: sphere, radius: 0.00005, position: [1.5, -0.5, 0]}\n"
      "start: [0.5, 0.2]\ngoal: [2.5, 0.2]\nresolution: 0.01\n",
      "svmp", 3);
  const auto& runs = run.results[0].runs;
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_TRUE(runs[0].result.warnings.empty() && runs[2].result.warnings.empty()) << "test premise";
  ASSERT_EQ(runs[1].result.warnings.size(), 1u) << "test premise";
  const std::string logged = "svmp warning (seed 2): " + runs[1].result.warnings[0];
  const size_t at = run.log.find(logged);
  ASSERT_NE(at, std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("warning", at + logged.size()), std::string::npos) << run.log;
}

// A path --simplify svpp keeps as planned says so in its record, not only in the log (a probe's
// finding): a slit 0.0015 wide in a turned wall, where the smoothed path is not proven free.
TEST(DriverOutput, APathTheSvmSmoothingKeepsSaysSoInItsRecord) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/unseen/rotgap2d_0015.yaml";
  Experiment run{cspace::loadScenario(path), {}, {}, {}};
  run.options.planners = {"svmp"};
  run.options.simplify = run.options.simplify_svm = true;
  std::ostringstream log;
  run.results = runExperiment(run.scenario, run.options, log);
  const RunRecord& r = run.results[0].runs.at(0);
  ASSERT_TRUE(r.result.solved()) << r.result.message;
  EXPECT_EQ(r.raw_length, r.path_length);
  ASSERT_EQ(r.result.warnings.size(), 1u) << log.str();
  EXPECT_EQ(r.result.warnings[0].rfind("--simplify svpp kept the path as planned: ", 0), 0u) << r.result.warnings[0];
  EXPECT_NE(log.str().find("path kept ("), std::string::npos) << log.str();
  EXPECT_EQ(log.str().find("warning: --simplify svpp"), std::string::npos) << "said twice:\n" << log.str();
}

// svpp's search angle steers the 2-D following only: a 3-D scene refuses it under --simplify svpp
// too, naming the field, as `--planners svpp` does.
TEST(DriverOutput, SvmSmoothingRefusesTheSearchAngleIn3d) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/svpp_3d10_01.yaml";
  DriverOptions options;
  options.planners = {"ompl-rrtconnect"};
  options.simplify = options.simplify_svm = true;
  options.overrides = {{"svpp.search_angle_deg", "90"}};
  std::ostringstream log;
  try {
    runExperiment(cspace::loadScenario(path), options, log);
    ADD_FAILURE() << "search_angle_deg taken in 3-D";
  } catch (const cspace::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("'planners.svpp.search_angle_deg': applies in 2-D only"), std::string::npos)
        << e.what();
  }
}

// A path with no obstacle in the scene has an infinite clearance, which JSON cannot hold: the record
// says "inf", the summary null, the table inf, and --merge reads the record back as infinite (it had
// read null as NaN; before that the file had held a bare inf and -nan, which no parser took).
TEST(DriverOutput, InfiniteClearanceIsValidJsonAndMergesBackInfinite) {
  const std::string text_scenario =
      "name: empty\nrobot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\nobstacles: []\n"
      "start: [0.1, 0.5]\ngoal: [0.9, 0.5]\nresolution: 0.01\n";
  const Experiment run = runText(text_scenario, "svmp", 2);
  ASSERT_EQ(run.results[0].solved(), 2);
  const fs::path dir = fs::temp_directory_path() / "svmp_driver_infinite_clearance_test";
  fs::create_directories(dir);
  const fs::path file = dir / "run.json", scenario = dir / "empty.yaml";
  std::ofstream(scenario) << text_scenario;
  writeJson(file.string(), run.scenario, run.options, run.results);
  const YAML::Node json = YAML::LoadFile(file.string())["results"][0];
  EXPECT_TRUE(json["min_clearance"]["mean"].IsNull());
  EXPECT_EQ(json["min_clearance"]["n"].as<int>(), 2);
  EXPECT_EQ(json["records"][0]["min_clearance"].as<std::string>(), "inf");
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(meanStd(statsOf({inf, inf}), 4), "inf");
  const MergedShards merged = mergeShards({file.string()}, scenario.string());
  ASSERT_EQ(merged.results[0].runs.size(), 2u);
  for (const RunRecord& r : merged.results[0].runs) EXPECT_EQ(r.min_clearance, inf);
  fs::remove_all(dir);
}

#ifdef SVMP_WITH_OMPL
// --time-limit holds for each query of a run: a query no planner solves (the start shut in a box)
// ends in a timeout, and the easy query after it still gets its own time and is solved. A limit for
// the whole run let such a query use it up, and RRTConnect then failed every later query untried.
TEST(DriverOutput, TimeLimitHoldsForEachQueryOnItsOwn) {
  const Experiment run = runText(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}\n"
      "obstacles:\n"
      "  - {name: left, shape: box, size: [0.2, 2.2, 1], position: [1, 2, 0]}\n"
      "  - {name: right, shape: box, size: [0.2, 2.2, 1], position: [3, 2, 0]}\n"
      "  - {name: bottom, shape: box, size: [2.2, 0.2, 1], position: [2, 1, 0]}\n"
      "  - {name: top, shape: box, size: [2.2, 0.2, 1], position: [2, 3, 0]}\n"
      "queries:\n"
      "  - {start: [2, 2], goal: [8, 8]}\n"
      "  - {start: [6, 5], goal: [8, 5]}\n"
      "resolution: 0.01\n",
      "ompl-rrtconnect", 1, 2.0);  // query 1 is impossible: it still times out
  const auto& records = run.results[0].runs;
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[0].result.status, planners::PlanStatus::kTimeout) << run.log;
  EXPECT_TRUE(records[1].result.solved()) << planners::planStatusName(records[1].result.status) << "\n" << run.log;
}
#endif

// --check warns of an obstacle thinner than what one resolution step can jump (a point robot: the
// step itself), naming it, and not of one thick enough.
TEST(DriverOutput, CheckWarnsOfObstaclesThinnerThanAStep) {
  const cspace::Scenario scenario = cspace::parseScenario(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n"
      "  - {name: foil, shape: box, size: [0.004, 0.6, 1], position: [0.5, 0.3, 0]}\n"
      "  - {name: plank, shape: box, size: [0.02, 0.3, 1], position: [0.5, 0.85, 0]}\n"
      "start: [0.1, 0.3]\ngoal: [0.9, 0.3]\nresolution: 0.01\n",
      "thin.yaml");
  std::ostringstream out;
  EXPECT_TRUE(printScenarioCheck(scenario, out));
  const std::string text = out.str();
  EXPECT_NE(text.find("warning    obstacle 'foil' is 0.004 thick"), std::string::npos) << text;
  EXPECT_EQ(text.find("'plank'", text.find("warning")), std::string::npos) << text;
}

// --check refuses what planning refuses: an obstacle's sample that does not hit it.
TEST(DriverOutput, CheckNamesASampleThatMissesItsObstacle) {
  const cspace::Scenario scenario = cspace::parseScenario(
      "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
      "obstacles:\n"
      "  - {name: hit, shape: box, size: [0.2, 0.2, 1], position: [0.3, 0.3, 0], sample: [0.3, 0.3]}\n"
      "  - {name: missed, shape: box, size: [0.2, 0.2, 1], position: [0.7, 0.7, 0], sample: [0.5, 0.5]}\n"
      "start: [0.1, 0.9]\ngoal: [0.9, 0.1]\nresolution: 0.01\n",
      "samples.yaml");
  std::ostringstream out;
  EXPECT_FALSE(printScenarioCheck(scenario, out));
  EXPECT_NE(out.str().find("sample     [0.3, 0.3] hits obstacle 'hit'"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("error      sample [0.5, 0.5] does NOT hit obstacle 'missed'"), std::string::npos)
      << out.str();
}

// --merge takes only what svmp-plan writes: every seed answering every query once, counts that are
// counts. A shard with one record too many once wrote past the end of the table's totals.
TEST(DriverOutput, MergeRefusesShardsThatAreNotOneRun) {
  const std::string scenario = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig3_5.yaml";
  cspace::Scenario fig35 = cspace::loadScenario(scenario);
  DriverOptions options;
  options.scenario = scenario;
  options.planners = {"prm"};
  options.runs = 2;
  std::ostringstream log;
  const auto results = runExperiment(fig35, options, log);
  const fs::path dir = fs::temp_directory_path() / "svmp_driver_merge_test";
  fs::create_directories(dir);
  const std::string good = (dir / "good.json").string();
  writeJson(good, fig35, options, results);
  EXPECT_EQ(mergeShards({good}, "").results[0].runs.size(), 2u);
  std::ifstream in(good);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // `text` with the first `from` after `after` replaced by `to`, written as `name`.
  auto variant = [&](const std::string& name, const std::string& from, const std::string& to,
                     const std::string& after = "") {
    std::string changed = text;
    const size_t at = changed.find(from, after.empty() ? 0 : changed.find(after));
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) changed.replace(at, from.size(), to);
    std::ofstream((dir / name).string()) << changed;
    return (dir / name).string();
  };
  // Each case: the shards merged and what the error must say.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      // Records are written compact ("key":value).
      {{variant("query.json", "\"query\":0,", "\"query\":1,")}, "query 1 is not one of the scenario's 1 queries"},
      {{variant("count.json", "\"collision_checks\":", "\"collision_checks\":-", "\"records\"")},
       "must be an integer in [0, "},
      // Integers that would wrap or round (a query 4294967296 had been read as 0, 0.9 as 0).
      {{variant("query_wraps.json", "\"query\":0,", "\"query\":4294967296,")}, "must be an integer in ["},
      {{variant("query_fraction.json", "\"query\":0,", "\"query\":0.9,")}, "must be an integer in ["},
      // What svmp-plan never writes: a solved record not certified, a negative time.
      {{variant("uncertified.json", "\"status\":\"failed\"", "\"status\":\"solved\"", "\"records\"")},
       "but not certified"},
      {{variant("negative_time.json", "\"time_ms\":", "\"time_ms\":-", "\"records\"")}, "field 'time_ms' must be a time in [0, 1e12] ms"},
      // Not a file at all (a pipe or /dev/zero would never end).
      {{dir.string()}, "not a regular file"},
      {{variant("threads.json", "\"threads\": 1", "\"threads\": -7")}, "not svmp-plan's options"},
      {{variant("planner.json", "\"planner\": \"prm\"", "\"planner\": \"prn\"")}, "planner 'prn' is not one"},
      // Shards of other code: the second from another revision.
      {{good, variant("revised.json", "\"revision\": \"", "\"revision\": \"x")},
       "shards of different code are not one run"},
      // A scenario file that changed after the shards ran it.
      {{variant("edited.json", "\"scenario_hash\": \"", "\"scenario_hash\": \"0")}, "has changed since the shards ran it"},
      // Shards whose planner ran with other parameters (the file's planners: section changed between them).
      {{good, variant("params.json", "\"parameters\": {", "\"parameters\": {\"zz\": \"1\", ")},
       "ran with other parameters"}};
  for (const auto& [files, expected] : cases) {
    try {
      mergeShards(files, "");
      ADD_FAILURE() << files.back() << " merged";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

// --check names link pairs it leaves out because they touch in every sampled configuration: a
// planar arm folded back over itself by its joint limits self-collides everywhere, and nothing said
// that its pair went unchecked.
TEST(DriverOutput, CheckWarnsOfSelfCollisionPairsLeftOut) {
  const cspace::Scenario scenario = cspace::parseScenario(
      "robot: {type: planar_arm, lengths: [1, 0.12, 1], widths: 0.1, "
      "limits: {lower: [-3, -0.5, 2.9], upper: [3, 0.5, 3.1416]}}\n"
      "start: [0, 0.5, 3.0]\ngoal: [1, 0.5, 3.0]\nresolution: 0.01\n",
      "folded.yaml");
  std::ostringstream out;
  printScenarioCheck(scenario, out);
  EXPECT_NE(out.str().find("warning    links 0 and 2 touch in every sampled configuration"), std::string::npos)
      << out.str();
}

TEST(DriverOutput, RandomQueriesAreValidSeededAndBuiltOncePerRun) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig3_5.yaml";
  cspace::Scenario scenario = cspace::loadScenario(path);
  const auto queries = randomQueries(scenario, 12, 5);
  ASSERT_EQ(queries.size(), 12u);
  const cspace::CollisionChecker checker(scenario.robot, scenario.environment, scenario.self_collision);
  for (const auto& q : queries) {
    EXPECT_TRUE(checker.isValid(q.start));
    EXPECT_TRUE(checker.isValid(q.goal));
    EXPECT_NE(q.start, q.goal);
  }
  const auto again = randomQueries(scenario, 12, 5);
  for (size_t i = 0; i < queries.size(); ++i) EXPECT_EQ(queries[i].start, again[i].start);
  EXPECT_NE(randomQueries(scenario, 1, 6).front().start, queries.front().start);

  scenario.queries = queries;
  DriverOptions options;
  options.scenario = path;
  options.planners = {"svmp"};
  options.runs = 2;
  std::ostringstream log, table;
  const auto results = runExperiment(scenario, options, log);
  ASSERT_EQ(results[0].runs.size(), 24u);
  int solved = 0;
  for (const auto& r : results[0].runs) {
    EXPECT_EQ(r.build_ms > 0, r.query == 0) << "query " << r.query;  // one build per run
    if (!r.result.solved()) continue;
    ++solved;
    EXPECT_TRUE(r.result.certified);
    EXPECT_TRUE(r.result.path.front() == queries[static_cast<size_t>(r.query)].start) << "query " << r.query;
    EXPECT_TRUE(r.result.path.back() == queries[static_cast<size_t>(r.query)].goal) << "query " << r.query;
  }
  EXPECT_GE(solved, 22);  // Fig 3.5's free space is one corridor: every pair is connected
  printTable(scenario, options, results, table);
  EXPECT_NE(table.str().find("12 queries per run, one build per run"), std::string::npos) << table.str();
}

// SVG text: markup escaped, and control characters, which XML 1.0 cannot carry even as
// references, replaced (a scenario named "fig\x01" gave files no XML parser read).
TEST(DriverOutput, SvgTextIsWellFormedXml) {
  EXPECT_EQ(escapeXml("a<b>&c"), "a&lt;b&gt;&amp;c");
  EXPECT_EQ(escapeXml(std::string("fig\x01\x1f\tend\n")), "fig??\tend\n");
  // U+FFFE and U+FFFF are valid UTF-8 (a scenario may name them) but not XML 1.0 characters.
  EXPECT_EQ(escapeXml("a\xEF\xBF\xBE" "b\xEF\xBF\xBF" "c\xEF\xBF\xBD"), "a?b?c\xEF\xBF\xBD");
}

// A build that fails fails every query of its run, and the first query's record keeps the build's
// time (a timed-out build was 0.0009 ms and ended the run's records). One --queries pair is built
// once too, not solved as a single query.
TEST(DriverOutput, AFailedBuildFailsEveryQueryAndKeepsItsTime) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig3_5.yaml";
  cspace::Scenario scenario = cspace::loadScenario(path);
  scenario.queries = randomQueries(scenario, 3, 5);
  DriverOptions options;
  options.scenario = path;
  options.planners = {"prm"};
  options.runs = 2;
  options.queries = 3;
  options.time_limit = 1e-6;
  std::ostringstream log, table;
  const auto results = runExperiment(scenario, options, log);
  ASSERT_EQ(results[0].runs.size(), 6u) << log.str();
  for (const auto& r : results[0].runs) {
    EXPECT_EQ(r.result.status, planners::PlanStatus::kTimeout) << "query " << r.query;
    EXPECT_EQ(r.build_ms > 0, r.query == 0) << "query " << r.query;
    if (r.query > 0) {
      EXPECT_EQ(r.result.collision_checks, 0u);  // the build's are counted once
    }
  }
  printTable(scenario, options, results, table);
  EXPECT_NE(table.str().find("0/6"), std::string::npos) << table.str();

  scenario.queries.resize(1);
  options.queries = 1;
  options.time_limit = 0;
  const auto one = runExperiment(scenario, options, log);
  ASSERT_EQ(one[0].runs.size(), 2u);
  for (const auto& r : one[0].runs) EXPECT_GT(r.build_ms, 0);
}

// Seed by seed, every planner in turn (so load that changes during a run slows each alike), and each
// planner's results are those it gives when run alone.
TEST(DriverOutput, PlannersRunSeedBySeedAndGiveWhatTheyGiveAlone) {
  const std::string path = std::string(SVMP_SOURCE_DIR) + "/bench/scenarios/thesis_fig3_5.yaml";
  const cspace::Scenario scenario = cspace::loadScenario(path);
  DriverOptions options;
  options.scenario = path;
  options.planners = {"svmp", "prm"};
  options.runs = 2;
  std::ostringstream log;
  const auto together = runExperiment(scenario, options, log);
  const std::string text = log.str();
  size_t at = 0;
  for (const std::string line : {"svmp seed 1:", "prm seed 1:", "svmp seed 2:", "prm seed 2:"}) {
    at = text.find(line, at);
    ASSERT_NE(at, std::string::npos) << line << " not in order in\n" << text;
  }
  for (size_t p = 0; p < 2; ++p) {
    DriverOptions alone_options = options;
    alone_options.planners = {options.planners[p]};
    std::ostringstream quiet;
    const auto alone = runExperiment(scenario, alone_options, quiet);
    ASSERT_EQ(together[p].runs.size(), alone[0].runs.size());
    for (size_t r = 0; r < alone[0].runs.size(); ++r) {
      EXPECT_EQ(together[p].runs[r].result.collision_checks, alone[0].runs[r].result.collision_checks);
      EXPECT_EQ(together[p].runs[r].result.path, alone[0].runs[r].result.path);
    }
  }
}

TEST(DriverOutput, FileNamesCannotLeaveTheirDirectory) {
  EXPECT_EQ(safeFileName("../../x"), "_.._x");
  EXPECT_EQ(safeFileName("a/b\\c d"), "a_b_c_d");
  EXPECT_EQ(safeFileName(".."), "_");
  // A name of any length (scenario names are free text) stays within a file name's 255 bytes, and
  // two long names that share their first 100 characters stay apart.
  const std::string a = safeFileName(std::string(300, 'L')), b = safeFileName(std::string(300, 'L') + "x");
  EXPECT_LE(a.size(), 120u);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.substr(0, 100), std::string(100, 'L'));
  EXPECT_EQ(jsonString("a\"b\\c\n\x01"), "\"a\\\"b\\\\c\\n\\u0001\"");
}

}  // namespace
}  // namespace svmp::experiments
