#!/usr/bin/env python3
"""svmp-plan --ompl-log through OMPL's own parser: runs svmp-plan with --ompl-log, --json and --paths,
turns the log into a SQLite database with ompl_benchmark_statistics (ompl-demos), reads it back and
asserts the same experiment, planners, parameters, runs and numbers as the JSON outputs: counts exactly,
times, lengths and clearances to the JSON's printed precision (10 significant digits).

usage: ompl_log_roundtrip.py SVMP_PLAN OMPL_BENCHMARK_STATISTICS SCENARIO WORKDIR
"""
import json
import math
import os
import sqlite3
import statistics
import subprocess
import sys

PLANNERS = ["svmp", "prm"]
# ompl::base::PlannerStatus of each of our statuses (planners/ompl/state_bridge.hpp omplStatus); 8 is ABORT.
OMPL_STATUS = {"solved": 6, "local_minimum": 5, "timeout": 4, "invalid_start": 1, "invalid_goal": 2}
RUNS = 3
SEED = 5


def close(a, b, what):
    if not math.isclose(a, b, rel_tol=2e-9, abs_tol=1e-12):
        raise AssertionError(f"{what}: log {a!r} != json {b!r}")


def equal(a, b, what):
    if a != b:
        raise AssertionError(f"{what}: log {a!r} != json {b!r}")


def main():
    plan, stats_tool, scenario, workdir = sys.argv[1:5]
    os.makedirs(workdir, exist_ok=True)
    log, db = os.path.join(workdir, "roundtrip.log"), os.path.join(workdir, "roundtrip.db")
    js, paths = os.path.join(workdir, "roundtrip.json"), os.path.join(workdir, "roundtrip_paths.json")
    for f in (log, db):
        if os.path.exists(f):
            os.remove(f)
    subprocess.run([plan, "--scenario", scenario, "--planners", ",".join(PLANNERS), "--runs", str(RUNS),
                    "--seed", str(SEED), "--set", "svmp.sigma=0.25", "--ompl-log", log, "--json", js,
                    "--paths", paths], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([stats_tool, "-d", db, log], check=True, stdout=subprocess.DEVNULL)
    summary, per_run = json.load(open(js)), json.load(open(paths))["runs"]
    c = sqlite3.connect(db)

    (name, runcount, seed, version), = c.execute("SELECT name, runcount, seed, version FROM experiments")
    equal(name, summary["scenario"], "experiment name")
    equal(runcount, RUNS, "runs per planner")
    equal(int(seed), SEED, "seed")
    equal(version.split()[0], "svmp", "library")

    configs = c.execute("SELECT id, name, settings FROM plannerConfigs ORDER BY id").fetchall()
    equal([n for _, n, _ in configs], [r["planner"] for r in summary["results"]], "planners")
    settings = dict(line.split(" = ") for line in configs[0][2].strip(";").split("\n;"))
    equal(settings["sigma"], "0.25", "svmp's --set parameter")
    for key in ("C", "k", "samples_per_tree", "kernel", "repair_rounds"):
        if key not in settings:
            raise AssertionError(f"svmp's parameter {key} is not in the log")

    equal(c.execute("SELECT description FROM enums WHERE name = 'status' AND value = 6").fetchone()[0],
          "Exact solution", "status enum")
    c.row_factory = sqlite3.Row
    for (pid, planner, _), result in zip(configs, summary["results"]):
        rows = c.execute("SELECT * FROM runs WHERE plannerid = ? ORDER BY id", (pid,)).fetchall()
        mine = [r for r in per_run if r["planner"] == planner]
        equal(len(rows), len(result["statuses"]), f"{planner}: runs")
        equal([r["svmp_status"] for r in rows], result["statuses"], f"{planner}: statuses")
        equal([r["seed"] for r in rows], [r["seed"] for r in mine], f"{planner}: seeds")
        equal(sum(r["solved"] for r in rows), result["solved"], f"{planner}: solved")
        equal(sum(r["correct_solution"] or 0 for r in rows), result["certified"], f"{planner}: certified")
        for r, p in zip(rows, mine):
            equal(r["status"], OMPL_STATUS.get(p["status"], 8), f"{planner}: status enum")
            if p["status"] == "solved":
                equal(r["solution_segments"], len(p["path"]) - 1, f"{planner}: segments")
                equal(r["approximate_solution"], 0, f"{planner}: approximate")

        def check(column, key, scale=1.0, solved_only=False):
            values = [r[column] * scale for r in rows if not solved_only or r["solved"]]
            want = result
            for part in key.split("."):
                want = want[part]
            equal(len(values), want["n"], f"{planner}: {column} count")
            if not values:
                return
            close(statistics.fmean(values), want["mean"], f"{planner}: {column} mean")
            close(statistics.median(values), want["median"], f"{planner}: {column} median")

        for column, key in (("collision_checks", "collision_checks"), ("local_planner_calls", "local_planner_calls"),
                            ("distance_queries", "distance_queries"), ("certified_segments", "certified_segments"),
                            ("repaired_stretches", "repaired_stretches"), ("exact_checks", "exact_checks"),
                            ("support_vectors", "support_vectors"), ("milestones", "milestones"),
                            ("graph_states", "milestones"),
                            ("graph_motions", "roadmap_edges")):
            check(column, key)
            ints = [r[column] for r in rows]
            if any(not isinstance(v, int) for v in ints):
                raise AssertionError(f"{planner}: {column} is not an integer column: {ints}")
        check("time", "time_ms", 1000.0)
        for phase in ("sampling", "training", "milestones", "roadmap", "query", "certify"):
            check(f"{phase}_time", f"phase_ms.{phase}", 1000.0)
        check("solution_length", "path_length", solved_only=True)
        check("solution_clearance", "min_clearance", solved_only=True)
        check("solution_smoothness", "smoothness", solved_only=True)
    print(f"ompl_log_roundtrip: {len(configs)} planners x {RUNS} runs agree between the log's database and the JSON")


if __name__ == "__main__":
    main()
