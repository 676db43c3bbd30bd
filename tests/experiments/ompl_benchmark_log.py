#!/usr/bin/env python3
"""svmp-ompl-benchmark end to end: SVMP beside OMPL's PRM and RRTConnect in ompl::tools::Benchmark, its
log parsed by ompl_benchmark_statistics; asserts every planner's runs are in the database, SVMP solved
each with a correct solution and a roadmap (graph states), our counters recorded for every planner and
SVMP's parameters (from the scenario file) among its settings. Every planner's paths are proven: on a wall
a hundredth of the resolution thick, RRTConnect's sampled motions step through it, and those runs are
recorded as neither certified nor correct.

usage: ompl_benchmark_log.py SVMP_OMPL_BENCHMARK OMPL_BENCHMARK_STATISTICS SCENARIO WORKDIR
"""
import os
import sqlite3
import subprocess
import sys

RUNS = 2


def main():
    binary, stats_tool, scenario, workdir = sys.argv[1:5]
    os.makedirs(workdir, exist_ok=True)
    log, db = os.path.join(workdir, "benchmark.log"), os.path.join(workdir, "benchmark.db")
    for f in (log, db):
        if os.path.exists(f):
            os.remove(f)
    subprocess.run([binary, "--scenario", scenario, "--log", log, "--runs", str(RUNS), "--time-limit", "5"],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([stats_tool, "-d", db, log], check=True, stdout=subprocess.DEVNULL)
    c = sqlite3.connect(db)
    names = [n for n, in c.execute("SELECT name FROM plannerConfigs ORDER BY id")]
    assert names == ["geometric_svmp", "geometric_PRM", "geometric_RRTConnect"], names
    for name in names:
        (runs, with_checks), = c.execute(
            "SELECT COUNT(*), SUM(collision_checks > 0) FROM runs JOIN plannerConfigs p ON plannerid = p.id "
            "WHERE p.name = ?", (name,))
        assert runs == RUNS and with_checks == RUNS, (name, runs, with_checks)
    (solved, correct, certified, states, settings), = c.execute(
        "SELECT SUM(solved), SUM(correct_solution), SUM(certified), MIN(graph_states), settings FROM runs "
        "JOIN plannerConfigs p ON plannerid = p.id WHERE p.name = 'geometric_svmp'")
    assert solved == RUNS and correct == RUNS and certified == RUNS, (solved, correct, certified)
    assert states > 10, states
    assert "sigma = " in settings and "samples_per_tree = " in settings, settings
    (uncertified_correct,), = c.execute("SELECT COUNT(*) FROM runs WHERE correct_solution = 1 AND certified = 0")
    assert uncertified_correct == 0, uncertified_correct
    c.close()

    wall, log, db = (os.path.join(workdir, f) for f in ("thin_wall.yaml", "thin_wall.log", "thin_wall.db"))
    with open(wall, "w") as f:
        f.write("name: thin_wall\n"
                "robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
                "obstacles:\n"
                "  - {name: wall, shape: box, size: [0.0001, 1.8, 1], position: [0.5, 0, 0]}\n"
                "start: [0.1037, 0.1]\ngoal: [0.9, 0.1]\nresolution: 0.01\n")
    for f in (log, db):
        if os.path.exists(f):
            os.remove(f)
    subprocess.run([binary, "--scenario", wall, "--log", log, "--runs", str(RUNS), "--time-limit", "5",
                    "--planners", "RRTConnect,svmp"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    subprocess.run([stats_tool, "-d", db, log], check=True, stdout=subprocess.DEVNULL)
    c = sqlite3.connect(db)
    rows = dict((name, (solved, certified, correct)) for name, solved, certified, correct in c.execute(
        "SELECT p.name, SUM(solved), SUM(certified), SUM(correct_solution) FROM runs "
        "JOIN plannerConfigs p ON plannerid = p.id GROUP BY p.name"))
    assert rows["geometric_RRTConnect"][0] == RUNS and rows["geometric_RRTConnect"][1] < RUNS, rows
    assert rows["geometric_RRTConnect"][2] == rows["geometric_RRTConnect"][1], rows
    assert rows["geometric_svmp"] == (RUNS, RUNS, RUNS), rows
    print(f"ompl_benchmark_log: {len(names)} planners x {RUNS} runs in the database; on a thin wall "
          f"RRTConnect {rows['geometric_RRTConnect'][1]} of {RUNS} certified")


if __name__ == "__main__":
    main()
