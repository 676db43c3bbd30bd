#include "bench/experiments/run_records.hpp"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include <sys/stat.h>

#include "bench/experiments/driver_options.hpp"
#include "planners/planner_registry.hpp"

namespace svmp::experiments {
namespace {

using nlohmann::json;

// JSON has no infinities or NaN: an infinity is written as the string "inf" or "-inf" (a path's
// clearance with no obstacle in the scene: read back by clearanceOf), NaN as null (get<double>).
json number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return std::isnan(v) ? json(nullptr) : json(v);
}

planners::PlanStatus statusFromName(const std::string& name, const std::string& where) {
  using planners::PlanStatus;
  for (PlanStatus s : {PlanStatus::kSolved, PlanStatus::kFailed, PlanStatus::kTimeout, PlanStatus::kInvalidStart,
                       PlanStatus::kInvalidGoal, PlanStatus::kInvalidInput, PlanStatus::kLocalMinimum})
    if (name == planners::planStatusName(s)) return s;
  throw std::runtime_error(where + ": unknown status '" + name + "'");
}

// obj[key] as T; errors name the file and the field's path.
template <class T>
T get(const json& obj, const std::string& key, const std::string& where) {
  const auto it = obj.find(key);
  if (it == obj.end()) throw std::runtime_error(where + ": field '" + key + "' missing");
  if constexpr (std::is_same_v<T, double>)
    if (it->is_null()) return std::numeric_limits<double>::quiet_NaN();
  // An integer read from a negative number, a fraction or one out of T's range would wrap or round
  // without a word (a query 4294967296 read as 0, 0.9 as 0).
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    // A non-negative integer is stored unsigned (read as int64 beyond 2^63 it would wrap negative).
    const bool fits = it->is_number_unsigned()
                          ? it->get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<T>::max())
                          : !std::is_unsigned_v<T> && it->is_number_integer() &&
                                it->get<std::int64_t>() >= static_cast<std::int64_t>(std::numeric_limits<T>::min());
    if (!fits)
      throw std::runtime_error(where + ": field '" + key + "' must be an integer in [" +
                               std::to_string(std::is_unsigned_v<T> ? 0 : std::numeric_limits<T>::min()) + ", " +
                               std::to_string(std::numeric_limits<T>::max()) + "], got " + it->dump());
  }
  try {
    return it->get<T>();
  } catch (const json::exception&) {
    throw std::runtime_error(where + ": field '" + key + "' has the wrong type: " + it->dump());
  }
}

// A record's min_clearance: a number, null or "inf" (only a clearance is ever infinite).
double clearanceOf(const json& j, const std::string& where) {
  if (const auto it = j.find("min_clearance"); it != j.end() && *it == "inf") return HUGE_VAL;
  return get<double>(j, "min_clearance", where);
}

RunRecord recordFromJson(const json& j, const std::string& where) {
  if (!j.is_object()) throw std::runtime_error(where + ": not an object");
  RunRecord r;
  planners::PlanResult& p = r.result;
  r.seed = get<std::uint64_t>(j, "seed", where);
  r.query = get<int>(j, "query", where);
  p.status = statusFromName(get<std::string>(j, "status", where), where + ".status");
  p.message = get<std::string>(j, "message", where);
  if (j.contains("warnings")) p.warnings = get<std::vector<std::string>>(j, "warnings", where);  // older files: none
  p.certified = get<bool>(j, "certified", where);
  p.certified_segments = get<std::uint64_t>(j, "certified_segments", where);
  p.collision_checks = get<std::uint64_t>(j, "collision_checks", where);
  p.local_planner_calls = get<std::uint64_t>(j, "local_planner_calls", where);
  p.distance_queries = get<std::uint64_t>(j, "distance_queries", where);
  p.repaired_stretches = get<int>(j, "repaired_stretches", where);
  if (p.repaired_stretches < 0)
    throw std::runtime_error(where + ": field 'repaired_stretches' must be a count, got " +
                             std::to_string(p.repaired_stretches));
  p.exact_checks = get<std::uint64_t>(j, "exact_checks", where);
  p.milestones = get<std::uint64_t>(j, "milestones", where);
  p.roadmap_edges = get<std::uint64_t>(j, "roadmap_edges", where);
  p.support_vectors = get<std::uint64_t>(j, "support_vectors", where);
  const json phases = get<json>(j, "phase_ms", where);
  const std::string in_phases = where + ".phase_ms";
  p.times.sampling_ms = get<double>(phases, "sampling", in_phases);
  p.times.training_ms = get<double>(phases, "training", in_phases);
  p.times.milestones_ms = get<double>(phases, "milestones", in_phases);
  p.times.roadmap_ms = get<double>(phases, "roadmap", in_phases);
  p.times.query_ms = get<double>(phases, "query", in_phases);
  p.times.certify_ms = get<double>(phases, "certify", in_phases);
  r.time_ms = get<double>(j, "time_ms", where);
  r.build_ms = get<double>(j, "build_ms", where);
  r.path_length = get<double>(j, "path_length", where);
  r.raw_length = get<double>(j, "raw_length", where);
  r.smoothness = get<double>(j, "smoothness", where);
  r.simplify_ms = get<double>(j, "simplify_ms", where);
  r.min_clearance = clearanceOf(j, where);
  // What svmp-plan never writes: a solved path it did not certify, a negative or endless time (1e12
  // ms is 31 years; beyond, a sum of them overflows to inf), a negative length or clearance (null,
  // read as NaN, is an unsolved run's).
  if (p.status == planners::PlanStatus::kSolved && !p.certified)
    throw std::runtime_error(where + ": status 'solved' but not certified (svmp-plan counts only certified paths)");
  for (const auto& [name, ms] :
       {std::pair{"time_ms", r.time_ms}, {"build_ms", r.build_ms}, {"simplify_ms", r.simplify_ms},
        {"phase_ms.sampling", p.times.sampling_ms}, {"phase_ms.training", p.times.training_ms},
        {"phase_ms.milestones", p.times.milestones_ms}, {"phase_ms.roadmap", p.times.roadmap_ms},
        {"phase_ms.query", p.times.query_ms}, {"phase_ms.certify", p.times.certify_ms}})
    if (!(ms >= 0 && ms <= 1e12))
      throw std::runtime_error(where + ": field '" + name + "' must be a time in [0, 1e12] ms, got " + std::to_string(ms));
  for (const auto& [name, v] : {std::pair{"path_length", r.path_length}, {"raw_length", r.raw_length},
                                {"min_clearance", r.min_clearance}, {"smoothness", r.smoothness}})
    if (v < 0 || (std::isinf(v) && (name == std::string("path_length") || name == std::string("raw_length"))))
      throw std::runtime_error(where + ": field '" + name + "' must be null or a number >= 0, got " + std::to_string(v));
  return r;
}

// A shard far beyond what svmp-plan writes (about 1 kB a record) would take the parser's memory many
// times over (a 240 MB file: 5.6 GB and rising); pipes and devices are no shards (/dev/zero never ends).
constexpr std::uintmax_t kMaxShardBytes = 256u << 20;

json readJsonFile(const std::string& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) throw std::runtime_error(file + ": cannot open: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(file + ": not a regular file (a shard is svmp-plan's --json file)");
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxShardBytes)
    throw std::runtime_error(file + ": " + std::to_string(st.st_size) + " bytes, more than a shard may have (" +
                             std::to_string(kMaxShardBytes >> 20) + " MiB)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file + ": cannot open: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw std::runtime_error(file + ": not JSON: " + e.what());
  }
}

// "{svmp.sigma=0.3, svmp.k=5}"; "{}" when empty.
std::string listed(const std::set<std::string>& overrides) {
  std::string out;
  for (const std::string& kv : overrides) out += (out.empty() ? "" : ", ") + kv;
  return "{" + out + "}";
}

// The fields every shard of one merge must share (the seed and the number of runs are what differ).
const char* const kSharedFields[] = {"scenario", "file",       "scenario_hash", "dof",     "queries", "random_queries",
                                     "threads",  "time_limit", "simplified",    "simplifier", "checker"};

// What the shards of one merge add up to, one file at a time.
struct ShardUnion {
  json first;                                                     // the first shard: fields all must share
  std::map<std::string, std::string> override_value;              // "svmp.sigma" -> "0.3"
  std::vector<std::pair<std::string, std::string>> overrides;      // in order of first appearance
  std::map<std::string, std::set<std::string>> planner_overrides;  // each planner's own --set values
  std::vector<PlannerRuns> results;                               // planners in order of first appearance
  std::set<std::uint64_t> seeds;                                  // the shards' --seed values
  std::map<std::string, std::set<std::string>> machines;          // host, cpu, simd -> the shards' values
  std::string started;                                            // the earliest shard's start

  void add(const std::string& file, const std::string& first_file) {
    const json shard = readJsonFile(file);
    if (!shard.is_object() || !shard.contains("results") || !shard["results"].is_array())
      throw std::runtime_error(file + ": not svmp-plan's JSON (no list 'results')");
    if (first.is_null()) first = shard;
    for (const char* field : kSharedFields) {
      if (!shard.contains(field))
        throw std::runtime_error(file + ": field '" + field + "' missing (written by an older svmp-plan? rerun "
                                 "the shard)");
      if (shard[field] != first[field])
        throw std::runtime_error(file + ": field '" + field + "' is " + shard[field].dump() + ", but " + first_file +
                                 " has " + first[field].dump());
    }
    // Shards of other code are not one run (an older svmp-plan wrote no revision).
    if (shard.value("revision", "") != first.value("revision", ""))
      throw std::runtime_error(file + ": field 'revision' is " + shard.value("revision", "(none)") + ", but " +
                               first_file + " has " + first.value("revision", "(none)") +
                               " (shards of different code are not one run)");
    for (const char* machine : {"host", "cpu", "simd"}) machines[machine].insert(shard.value(machine, "(not recorded)"));
    const std::string shard_started = shard.value("started", "(not recorded)");
    if (started.empty() || shard_started < started) started = shard_started;  // "YYYY-MM-DD HH:MM:SS" sorts
    seeds.insert(get<std::uint64_t>(shard, "seed", file));
    const std::set<std::string> shard_overrides = addOverrides(file, list(shard, "overrides", file));
    const json& shard_results = shard["results"];
    for (size_t p = 0; p < shard_results.size(); ++p) {
      const std::string where = file + ": results[" + std::to_string(p) + "]";
      const std::string planner = get<std::string>(shard_results[p], "planner", where);
      std::set<std::string> own;
      for (const std::string& kv : shard_overrides)
        if (kv.rfind(planner + ".", 0) == 0) own.insert(kv);
      const auto [known, new_planner] = planner_overrides.emplace(planner, own);
      if (!new_planner && known->second != own)
        throw std::runtime_error(where + ": planner '" + planner + "' ran with --set " + listed(own) +
                                 ", in another shard with " + listed(known->second) +
                                 " (different parameter values are different runs)");
      auto runs = std::find_if(results.begin(), results.end(), [&](const PlannerRuns& r) { return r.planner == planner; });
      if (runs == results.end()) runs = results.insert(results.end(), PlannerRuns{planner, {}, {}});
      // The parameters a planner ran with (the file's planners: section may have changed between shards).
      std::map<std::string, std::string> parameters;
      if (const auto it = shard_results[p].find("parameters"); it != shard_results[p].end() && it->is_object())
        for (const auto& [key, value] : it->items())
          if (value.is_string()) parameters[key] = value.get<std::string>();
      if (runs->runs.empty())
        runs->parameters = parameters;
      else if (runs->parameters != parameters)
        throw std::runtime_error(where + ": planner '" + planner + "' ran with other parameters than in " + first_file +
                                 " (different parameter values are different runs)");
      const json& records = list(shard_results[p], "records", where);
      for (size_t r = 0; r < records.size(); ++r)
        runs->runs.push_back(recordFromJson(records[r], where + ".records[" + std::to_string(r) + "]"));
    }
  }

  // One value per --set key across all shards; returns this shard's "KEY=VALUE" entries.
  std::set<std::string> addOverrides(const std::string& file, const json& entries) {
    std::set<std::string> texts;
    for (const json& kv : entries) {
      const std::string text = kv.is_string() ? kv.get<std::string>() : "";
      const size_t eq = text.find('=');
      if (eq == std::string::npos) throw std::runtime_error(file + ": field 'overrides': bad entry " + kv.dump());
      const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
      const auto [it, added] = override_value.emplace(key, value);
      if (added) overrides.emplace_back(key, value);
      else if (it->second != value)
        throw std::runtime_error(file + ": field 'overrides': " + text + ", but another shard has " + key + "=" +
                                 it->second + " (different parameter values are different runs)");
      texts.insert(text);
    }
    return texts;
  }

  static const json& list(const json& obj, const std::string& key, const std::string& where) {
    const auto it = obj.find(key);
    if (it == obj.end() || !it->is_array()) throw std::runtime_error(where + ": field '" + key + "' is not a list");
    return *it;
  }
};

}  // namespace

std::string runRecordJson(const RunRecord& record) {
  const planners::PlanResult& p = record.result;
  const json j = {{"seed", record.seed},
                  {"query", record.query},
                  {"status", planners::planStatusName(p.status)},
                  {"message", p.message},
                  {"warnings", p.warnings},
                  {"certified", p.certified},
                  {"certified_segments", p.certified_segments},
                  {"collision_checks", p.collision_checks},
                  {"local_planner_calls", p.local_planner_calls},
                  {"distance_queries", p.distance_queries},
                  {"repaired_stretches", p.repaired_stretches},
                  {"exact_checks", p.exact_checks},
                  {"milestones", p.milestones},
                  {"roadmap_edges", p.roadmap_edges},
                  {"support_vectors", p.support_vectors},
                  {"phase_ms",
                   {{"sampling", number(p.times.sampling_ms)},
                    {"training", number(p.times.training_ms)},
                    {"milestones", number(p.times.milestones_ms)},
                    {"roadmap", number(p.times.roadmap_ms)},
                    {"query", number(p.times.query_ms)},
                    {"certify", number(p.times.certify_ms)}}},
                  {"time_ms", number(record.time_ms)},
                  {"build_ms", number(record.build_ms)},
                  {"path_length", number(record.path_length)},
                  {"raw_length", number(record.raw_length)},
                  {"smoothness", number(record.smoothness)},
                  {"simplify_ms", number(record.simplify_ms)},
                  {"min_clearance", number(record.min_clearance)}};
  return j.dump();
}

std::string overridesJson(const DriverOptions& options) {
  json list = json::array();
  for (const auto& [key, value] : options.overrides) list.push_back(key + "=" + value);
  return list.dump();
}

MergedShards mergeShards(const std::vector<std::string>& files, const std::string& scenario_file) {
  if (files.empty()) throw std::runtime_error("flag --merge: no shard files");
  ShardUnion shards;
  for (const std::string& file : files) {
    try {
      shards.add(file, files.front());
    } catch (const json::exception& e) {  // a value of an unexpected kind deeper in the file
      throw std::runtime_error(file + ": not svmp-plan's JSON: " + e.what());
    }
  }
  const json& first = shards.first;
  std::vector<PlannerRuns>& results = shards.results;
  // Both are drawn from --seed as a whole: shards with different seeds planned different problems.
  if (shards.seeds.size() > 1 && get<int>(first, "random_queries", files.front()) > 0)
    throw std::runtime_error("flag --merge: the shards drew their --queries from different seeds, so they answer "
                             "different queries and are not one run");
  if (shards.seeds.size() > 1 && get<std::string>(first, "checker", files.front()) != "fcl")
    throw std::runtime_error("flag --merge: the shards trained their " + first["checker"].get<std::string>() +
                             " proxy from different seeds, so they planned on different checkers and are not one run");

  // Each planner's seeds must be one contiguous range without repeats, the same for every planner.
  std::uint64_t lowest = 0, highest = 0;
  for (PlannerRuns& runs : results) {
    std::sort(runs.runs.begin(), runs.runs.end(), [](const RunRecord& a, const RunRecord& b) {
      return a.seed != b.seed ? a.seed < b.seed : a.query < b.query;
    });
    if (runs.runs.empty()) throw std::runtime_error("flag --merge: planner '" + runs.planner + "' has no runs");
    for (size_t i = 1; i < runs.runs.size(); ++i) {
      const RunRecord &a = runs.runs[i - 1], &b = runs.runs[i];
      if (a.seed == b.seed && a.query == b.query)
        throw std::runtime_error("flag --merge: planner '" + runs.planner + "': seed " + std::to_string(a.seed) +
                                 " appears in two shards");
      if (b.seed > a.seed + 1)
        throw std::runtime_error("flag --merge: planner '" + runs.planner + "': seeds " + std::to_string(a.seed + 1) +
                                 ".." + std::to_string(b.seed - 1) + " are in no shard");
    }
    const std::uint64_t lo = runs.runs.front().seed, hi = runs.runs.back().seed;
    if (&runs != &results.front() && (lo != lowest || hi != highest))
      throw std::runtime_error("flag --merge: planner '" + runs.planner + "' covers seeds " + std::to_string(lo) + ".." +
                               std::to_string(hi) + ", planner '" + results.front().planner + "' " +
                               std::to_string(lowest) + ".." + std::to_string(highest));
    lowest = lo, highest = hi;
  }

  if (results.empty()) throw std::runtime_error("flag --merge: the shards hold no planner's runs");

  MergedShards merged;
  // The shards' version and revision (one), the earliest start; each machine field lists the shards' values.
  merged.provenance = {first.value("version", "(not recorded)"), first.value("revision", "(not recorded)"),
                       shards.started, "", "", ""};
  for (auto [field, value] : {std::pair{"host", &merged.provenance.host}, std::pair{"cpu", &merged.provenance.cpu},
                              std::pair{"simd", &merged.provenance.simd}})
    for (const std::string& v : shards.machines[field]) *value += (value->empty() ? "" : "; ") + v;
  const std::string file = scenario_file.empty() ? get<std::string>(first, "file", files.front()) : scenario_file;
  merged.scenario = cspace::loadScenario(file);
  if (merged.scenario.name != get<std::string>(first, "scenario", files.front()) ||
      merged.scenario.robot->dof() != get<int>(first, "dof", files.front()))
    throw std::runtime_error(file + ": scenario '" + merged.scenario.name + "' is not the shards' scenario " +
                             first["scenario"].dump());
  if (merged.scenario.content_hash != get<std::string>(first, "scenario_hash", files.front()))
    throw std::runtime_error(file + ": has changed since the shards ran it (its hash is " +
                             merged.scenario.content_hash + ", the shards' " + first["scenario_hash"].dump() +
                             "); rerun the shards or pass the file they ran");
  DriverOptions& o = merged.options;
  o.scenario = file;
  for (const PlannerRuns& runs : results) o.planners.push_back(runs.planner);
  o.runs = static_cast<int>(highest - lowest + 1);
  o.seed = lowest;
  o.threads = get<int>(first, "threads", files.front());
  o.time_limit = get<double>(first, "time_limit", files.front());
  o.queries = get<int>(first, "random_queries", files.front());
  o.checker = get<std::string>(first, "checker", files.front());
  o.simplify = get<bool>(first, "simplified", files.front());
  const std::string simplifier = get<std::string>(first, "simplifier", files.front());
  o.simplify_svm = simplifier == "svpp";
  o.overrides = shards.overrides;
  if (o.threads < 1 || !(o.time_limit >= 0) || o.queries < 0 || !isCheckerName(o.checker) ||
      (simplifier != "none" && simplifier != "shortcut" && simplifier != "svpp") ||
      o.simplify != (simplifier != "none"))
    throw std::runtime_error(files.front() + ": not svmp-plan's options: threads " + std::to_string(o.threads) +
                             ", time_limit " + first["time_limit"].dump() + ", random_queries " +
                             std::to_string(o.queries) + ", checker '" + o.checker + "', simplifier '" + simplifier + "'");
  const std::vector<std::string> known = planners::plannerNames();
  for (const std::string& planner : o.planners)
    if (std::find(known.begin(), known.end(), planner) == known.end())
      throw std::runtime_error("flag --merge: planner '" + planner + "' is not one of this build's planners");
  if (o.queries > 0) merged.scenario.queries = randomQueries(merged.scenario, o.queries, o.seed);
  if (merged.scenario.queries.size() != get<size_t>(first, "queries", files.front()))
    throw std::runtime_error(file + ": has " + std::to_string(merged.scenario.queries.size()) +
                             " queries, the shards " + first["queries"].dump());
  // Every planner: each seed of the range answered every query once (the table sums a run's queries).
  const size_t queries = merged.scenario.queries.size();
  for (const PlannerRuns& runs : results) {
    for (size_t k = 0; k < runs.runs.size(); ++k) {
      const RunRecord& r = runs.runs[k];
      if (r.query < 0 || static_cast<size_t>(r.query) >= queries)
        throw std::runtime_error("flag --merge: planner '" + runs.planner + "', seed " + std::to_string(r.seed) +
                                 ": query " + std::to_string(r.query) + " is not one of the scenario's " +
                                 std::to_string(queries) + " queries");
    }
    if (runs.runs.size() != static_cast<size_t>(o.runs) * queries)
      throw std::runtime_error("flag --merge: planner '" + runs.planner + "' has " + std::to_string(runs.runs.size()) +
                               " records, " + std::to_string(o.runs) + " seeds x " + std::to_string(queries) +
                               " queries make " + std::to_string(static_cast<size_t>(o.runs) * queries));
  }
  merged.results = std::move(results);
  return merged;
}

}  // namespace svmp::experiments
