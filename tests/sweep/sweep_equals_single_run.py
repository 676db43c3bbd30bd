#!/usr/bin/env python3
"""ctest sweep_equals_single_run: a 4-shard sweep run by GNU parallel and merged gives the single run.

One svmp-plan run over seeds S..S+N-1 and `scripts/sweep` over the same seeds in 4 shards per planner
(the planners whose runs repeat for a seed: svmp, prm and every OMPL planner but ompl-prm): the
merged JSON has the same per-run records and the same aggregates, and the merged table the same rows,
apart from wall-clock times. A rerun skips finished shards and reruns a missing or truncated one; svmp-plan --merge refuses seeds
missing or repeated, different parameter values, and shards whose --seed trained different proxies.
Usage: sweep_equals_single_run.py SOURCE_DIR SVMP_PLAN WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

SOURCE, DRIVER, WORK = sys.argv[1:4]
SWEEP = os.path.join(SOURCE, "scripts", "sweep")
SCENARIO = os.path.join(SOURCE, "bench", "scenarios", "thesis_fig3_5.yaml")
# The planners whose runs repeat exactly for a seed (ompl-prm grows by wall time; docs/architecture.md
# "Determinism").
PLANNERS, SEED, RUNS = "svmp,prm,ompl-rrtconnect,ompl-lazyprm,ompl-fmt,ompl-rrt,ompl-sbl,ompl-rrtstar,ompl-informedrrtstar", 3, 10
SHARDS = 4 * len(PLANNERS.split(","))
TIME_FIELDS = {"time_ms", "build_ms", "query_ms", "simplify_ms", "phase_ms", "started"}
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message)


def run(*command, expect=0):
    """`expect` None: any non-zero status."""
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if (done.returncode == 0) if expect is None else (done.returncode != expect):
        sys.exit(f"{' '.join(command)}: status {done.returncode}, expected {expect}\n{done.stdout}{done.stderr}")
    return done


def without_times(value):
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if k not in TIME_FIELDS}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def table_rows(text):
    """The table with the time column (fixed width, in code points) blanked."""
    lines = text.strip("\n").split("\n")
    header = lines[:2]
    rows = [line[:106] + line[126:] for line in lines[3:]]
    return header, lines[2], rows


def shard_mtimes(directory):
    shards = os.path.join(directory, "shards")
    return {f: os.stat(os.path.join(shards, f)).st_mtime_ns for f in sorted(os.listdir(shards))}


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
single_json = os.path.join(WORK, "single.json")
single = run(DRIVER, "--scenario", SCENARIO, "--planners", PLANNERS, "--seed", str(SEED), "--runs", str(RUNS),
             "--json", single_json).stdout
sweep = os.path.join(WORK, "sweep")
run(SWEEP, "plan", sweep, "--scenario", SCENARIO, "--planners", PLANNERS, "--seed", str(SEED), "--runs", str(RUNS),
    "--shards", "4", "--driver", DRIVER)
out = run(SWEEP, "local", sweep, "--jobs", "2").stdout
check(f"running {SHARDS}" in out, f"{SHARDS} shards (4 seed ranges per planner) run, got: {out}")
merged_text = run(SWEEP, "merge", sweep).stdout
with open(single_json) as f:
    expected = json.load(f)
with open(os.path.join(sweep, "merged", "thesis_fig3_5.json")) as f:
    merged = json.load(f)

# The merged JSON: header, per-run records (seed order) and aggregates equal the single run's.
for key in ("scenario", "file", "dof", "runs", "queries", "seed", "threads", "simplified", "checker", "overrides",
            "version", "revision", "host", "cpu", "simd"):
    check(merged[key] == expected[key], f"header field {key}: merged {merged[key]!r}, single {expected[key]!r}")
check([r["planner"] for r in merged["results"]] == PLANNERS.split(","), "planners in the single run's order")
for got, want in zip(merged["results"], expected["results"]):
    name = want["planner"]
    check([r["seed"] for r in got["records"]] == list(range(SEED, SEED + RUNS)), f"{name}: records in seed order")
    check(without_times(got["records"]) == without_times(want["records"]), f"{name}: per-run records differ")
    check(without_times(got) == without_times(want), f"{name}: aggregates differ")
    check(want["solved"] > 0, f"{name}: the single run solves something (else the comparison says little)")
# The merged table: same header and rows, times apart.
with open(os.path.join(sweep, "merged", "thesis_fig3_5.txt")) as f:
    merged_table = f.read()
check(merged_table in merged_text, "merge prints the table it writes")
check(table_rows(merged_table) == table_rows(single), f"tables differ:\n{merged_table}\nvs\n{single}")

# A rerun skips finished shards; a missing or truncated shard is rerun, and only it.
before = shard_mtimes(sweep)
out = run(SWEEP, "local", sweep).stdout
check("running 0" in out and shard_mtimes(sweep) == before, f"a rerun skips every finished shard: {out}")
names = sorted(before)
os.remove(os.path.join(sweep, "shards", names[0]))
with open(os.path.join(sweep, "shards", names[1]), "r+") as f:
    f.truncate(100)
out = run(SWEEP, "local", sweep).stdout
after = shard_mtimes(sweep)
check("running 2" in out, f"the missing and the truncated shard run again: {out}")
check(all(after[n] == before[n] for n in names[2:]), "the other shards are untouched")
run(SWEEP, "merge", sweep)
with open(os.path.join(sweep, "merged", "thesis_fig3_5.json")) as f:
    check(without_times(json.load(f)) == without_times(expected), "merged again after the rerun: still the single run")

# The Slurm script: one array task per shard; a task runs its shard (here without Slurm, as sbatch would).
run(SWEEP, "slurm", sweep, "--time", "00:10:00")
with open(os.path.join(sweep, "sweep.sbatch")) as f:
    script = f.read()
check(f"#SBATCH --array=0-{SHARDS - 1}\n" in script and "#SBATCH --time=00:10:00" in script, f"array script:\n{script}")
os.remove(os.path.join(sweep, "shards", names[5]))
with open(os.path.join(sweep, "plan.json")) as f:
    plan = json.load(f)
task = next(i for i, s in enumerate(plan["shards"]) if s["json"] == "shards/" + names[5])
subprocess.run(["bash", os.path.join(sweep, "sweep.sbatch")], env={**os.environ, "SLURM_ARRAY_TASK_ID": str(task)},
               check=True, stdout=subprocess.DEVNULL)
check(os.path.exists(os.path.join(sweep, "shards", names[5])), "the array task ran its shard")
check(shard_mtimes(sweep)[names[4]] == after[names[4]], "the array task touched no other shard")


# svmp-plan --merge refuses what is not one run.
def shards_of(planner):  # in seed order
    return [os.path.join(sweep, s["json"]) for s in plan["shards"] if s["planner"] == planner]


svmp_shards, prm_shards = shards_of("svmp"), shards_of("prm")
err = run(DRIVER, "--merge", svmp_shards[0], *svmp_shards[2:], expect=2).stderr
check("seeds 6..8 are in no shard" in err, f"a gap in the seeds is refused: {err}")
err = run(DRIVER, "--merge", *svmp_shards, *prm_shards[:-1], expect=2).stderr
check("covers seeds 3..10" in err, f"planners over different seeds are refused: {err}")
err = run(DRIVER, "--merge", *svmp_shards, svmp_shards[0], expect=2).stderr
check("appears in two shards" in err, f"a repeated shard is refused: {err}")
# Values svmp-plan never writes (a probe's edits): a negative length or clearance, an endless time.
for field, value, said in (("path_length", -5, "'path_length' must be null or a number >= 0"),
                           ("min_clearance", -1, "'min_clearance' must be null or a number >= 0"),
                           ("time_ms", 1e308, "'time_ms' must be a time in [0, 1e12] ms")):
    with open(svmp_shards[0]) as f:
        edited = json.load(f)
    edited["results"][0]["records"][0][field] = value
    bad = os.path.join(WORK, f"bad_{field}.json")
    with open(bad, "w") as f:
        json.dump(edited, f)
    err = run(DRIVER, "--merge", bad, *svmp_shards[1:], expect=2).stderr
    check(said in err, f"a record with {field} = {value} is refused: {err}")
other = os.path.join(WORK, "sigma.json")
run(DRIVER, "--scenario", SCENARIO, "--planners", "svmp", "--seed", "100", "--runs", "1", "--set", "svmp.sigma=0.9",
    "--json", other)
err = run(DRIVER, "--merge", *svmp_shards, other, expect=2).stderr
check("svmp.sigma" in err, f"shards with other --set values are refused: {err}")
proxies = [os.path.join(WORK, f"proxy{seed}.json") for seed in (1, 2)]
for seed, file in zip((1, 2), proxies):
    run(DRIVER, "--scenario", SCENARIO, "--planners", "svmp", "--checker", "fastron-rbf", "--seed", str(seed),
        "--json", file)
err = run(DRIVER, "--merge", *proxies, expect=2).stderr
check("proxy from different seeds" in err, f"proxy checkers trained from different seeds are refused: {err}")
err = run(SWEEP, "plan", os.path.join(WORK, "refused"), "--scenario", SCENARIO, "--", "--checker", "fastron-fk",
          expect=2).stderr
check("trained from --seed" in err, f"the sweep refuses a proxy checker: {err}")
# A bad planner parameter fails the plan, before any shard runs (svmp-plan --check).
err = run(SWEEP, "plan", os.path.join(WORK, "bad_param"), "--scenario", SCENARIO, "--planners", "svmp",
          "--param", "svmp.sigma=-1", "--driver", DRIVER, expect=2).stderr
check("planners.svmp.sigma" in err, f"the plan names the bad parameter: {err}")
# A failing shard (its scenario broken after the plan) fails `local` (naming it, its log holding
# svmp-plan's error), `status` (exit 1, each shard marked failed) and the merge.
failing = os.path.join(WORK, "failing")
broken = os.path.join(WORK, "broken.yaml")
shutil.copy(SCENARIO, broken)
run(SWEEP, "plan", failing, "--scenario", broken, "--planners", "svmp", "--runs", "2", "--shards", "2",
    "--driver", DRIVER)
with open(broken, "w") as f:
    f.write("robot: {type: point}\n")
err = run(SWEEP, "local", failing, expect=None).stderr
check("2 shard(s) not finished" in err, f"failed shards are reported: {err}")
with open(os.path.join(failing, "logs", "broken_svmp_seeds1-1.log")) as f:
    check("broken.yaml" in f.read(), "the shard's log holds svmp-plan's error")
out = run(SWEEP, "status", failing, expect=1).stdout
check(out.count("failed (exit 2") == 2 and "2 failed" in out, f"status marks the failed shards: {out}")
check("not finished" in run(SWEEP, "merge", failing, expect=2).stderr, "merge refuses unfinished shards")
err = run(DRIVER, "--merge", *svmp_shards, "--runs", "3", expect=2).stderr
check("--runs" in err, f"run flags with --merge are refused: {err}")

if failures:
    sys.exit(f"{len(failures)} check(s) failed")
print("sweep equals the single run")
