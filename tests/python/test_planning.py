"""svmp.load_scenario and svmp.plan: a plan's path runs from the scenario's start to its goal and every
segment passes a dense re-check with the module's exact collision check; a seed gives the same path
again and the same numbers as svmp-plan; bad scenarios, parameters and points raise ValueError with the
library's message."""
import json
import os
import pathlib
import subprocess

import numpy as np

import pytest

import svmp
from conftest import scenario_path

DETERMINISTIC = ["svmp", "prm", "ompl-rrtconnect", "ompl-lazyprm", "ompl-fmt"]  # repeat for a seed


def dense_recheck(scenario, path, step):
    """Every configuration at most `step` apart (weighted metric) along each segment is free."""
    checks = 0
    for a, b in zip(path[:-1], path[1:]):
        pieces = max(1, int(np.ceil(scenario.distance(a, b) / step)))
        for t in np.linspace(0.0, 1.0, pieces + 1):
            assert scenario.check(a + t * (b - a)) == 0, f"segment {a} -> {b} collides at t = {t}"
            checks += 1
    return checks


def test_scenario_exposes_the_file(fig35):
    assert (fig35.name, fig35.dof, fig35.resolution) == ("thesis_fig3_5", 2, 0.05)
    start, goal = fig35.queries[0]
    np.testing.assert_array_equal(start, [1.0, 5.0])
    np.testing.assert_array_equal(goal, [9.0, 5.0])
    np.testing.assert_array_equal(fig35.lower, [0, 0])
    assert fig35.check([5.0, 3.0]) == 1 and fig35.check([5.0, 8.0]) == 2  # inside the lower, upper block
    assert fig35.obstacles[0] == "lower" and len(fig35.obstacles) >= 2
    assert fig35.check([5.0, 6.15]) == 0 and fig35.clearance([5.0, 6.15]) == pytest.approx(0.15, abs=1e-5)
    assert fig35.distance([0, 0], [3, 4]) == pytest.approx(5.0)


@pytest.mark.parametrize("planner", DETERMINISTIC + ["ompl-rrt", "local"])
def test_path_joins_start_and_goal_and_passes_a_dense_recheck(fig35, planner):
    plan = svmp.plan(fig35, planner, seed=2)
    if planner in ("svmp", "ompl-rrtconnect"):  # these solve fig 3.5 at seed 2; the others may not
        assert plan.solved, plan.message
    if not plan.solved:
        assert plan.path.shape == (0, 2) and plan.message
        return
    start, goal = fig35.queries[0]
    assert plan.certified and plan.status == "solved"
    assert plan.path.shape[1] == 2 and len(plan.path) >= 2
    np.testing.assert_array_equal(plan.path[0], start)
    np.testing.assert_array_equal(plan.path[-1], goal)
    assert dense_recheck(fig35, plan.path, fig35.resolution / 10) > len(plan.path)
    length = sum(fig35.distance(a, b) for a, b in zip(plan.path[:-1], plan.path[1:]))
    assert plan.counters["path_length"] == pytest.approx(length, rel=1e-12)
    assert plan.counters["collision_checks"] > 0 and plan.counters["min_clearance"] >= 0


def test_arm_path_passes_a_dense_recheck():
    arm = svmp.load_scenario(scenario_path("thesis_fig4_4.yaml"))
    plan = svmp.plan(arm, "svmp", seed=1)
    assert plan.solved, plan.message
    assert plan.path.shape[1] == arm.dof == 5
    start, goal = arm.queries[0]
    np.testing.assert_array_equal(plan.path[0], start)
    np.testing.assert_array_equal(plan.path[-1], goal)
    dense_recheck(arm, plan.path, arm.resolution / 4)


@pytest.mark.parametrize("planner", DETERMINISTIC)
def test_same_seed_same_path(fig35, planner):
    first, again = svmp.plan(fig35, planner, seed=5), svmp.plan(fig35, planner, seed=5)
    np.testing.assert_array_equal(first.path, again.path)
    for key in ("collision_checks", "local_planner_calls", "milestones", "roadmap_edges"):
        assert first.counters[key] == again.counters[key]
    other = svmp.plan(fig35, planner, seed=6)
    assert other.counters["collision_checks"] != first.counters["collision_checks"] or \
        not np.array_equal(other.path, first.path)


def test_plan_equals_svmp_plan_for_the_same_seed_and_set(fig35, tmp_path):
    driver = os.environ.get("SVMP_PLAN", "")
    if not os.access(driver, os.X_OK):
        pytest.skip("SVMP_PLAN not set (run through ctest)")
    out = tmp_path / "r.json"
    subprocess.run([driver, "--scenario", fig35.path, "--planners", "svmp", "--seed", "4", "--runs", "1",
                    "--set", "svmp.sigma=0.4", "--json", str(out)], check=True, capture_output=True)
    record = json.loads(out.read_text())["results"][0]["records"][0]
    plan = svmp.plan(fig35, "svmp", seed=4, params={"sigma": 0.4})
    assert plan.status == record["status"]
    for key in ("collision_checks", "local_planner_calls", "distance_queries", "milestones", "support_vectors"):
        assert plan.counters[key] == record[key], key
    assert plan.counters["path_length"] == record["path_length"]
    assert svmp.plan(fig35, "svmp", seed=4).counters["support_vectors"] != record["support_vectors"]


def test_bad_scenario_raises_with_the_loaders_message(tmp_path):
    with pytest.raises(svmp.ScenarioError, match="cannot open"):
        svmp.load_scenario(str(tmp_path / "missing.yaml"))
    bad = tmp_path / "bad.yaml"
    bad.write_text("robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
                   "start: [0.5, .nan]\ngoal: [0.9, 0.9]\nresolution: 0.01\n")
    with pytest.raises(ValueError, match=r"bad\.yaml.*start"):
        svmp.load_scenario(str(bad))
    # A NUL byte had cut the name short in C: 'bad.yaml\0/x' loaded bad.yaml's neighbour silently.
    with pytest.raises(ValueError, match="cannot hold a NUL byte"):
        svmp.load_scenario(str(bad) + "\0/../other.yaml")
    with pytest.raises(ValueError, match="cannot be encoded in the file system's encoding"):
        svmp.load_scenario("a\ud800.yaml")  # a lone surrogate
    # A name not in UTF-8 reaches the file system as given (the loader names it), not as ''.
    with pytest.raises(svmp.ScenarioError, match="cannot open"):
        svmp.load_scenario(os.fsencode(str(tmp_path)) + b"/\xff.yaml")


def test_bad_plan_arguments_raise_value_error(fig35):
    with pytest.raises(ValueError, match="unknown planner 'rrt-star'"):
        svmp.plan(fig35, "rrt-star")
    with pytest.raises(ValueError, match="sigma"):
        svmp.plan(fig35, "svmp", params={"sigma": -1})
    with pytest.raises(ValueError, match=r"params\['samplez'\] = 10: field 'planners.prm.samplez'"):
        svmp.plan(fig35, "prm", params={"samplez": 10})  # in Python's terms, not the flag's
    with pytest.raises(ValueError, match="simplify is 'shortcut': expected False, True or 'svpp'"):
        svmp.plan(fig35, "svmp", simplify="shortcut")
    with pytest.raises(ValueError, match="params: svmp.sigma is already set to '0.4'"):
        svmp.plan(fig35, "svmp", params={"sigma": 0.4, "svmp.sigma": 0.5})
    with pytest.raises(ValueError, match="query is 1: the scenario has 1 query"):
        svmp.plan(fig35, "svmp", query=1)
    with pytest.raises(ValueError, match=r"seed is -1: must be in \[0, 2\^62\]"):
        svmp.plan(fig35, "svmp", seed=-1)
    with pytest.raises(ValueError, match=r"seed is 9223372036854775808: must be in"):
        svmp.plan(fig35, "svmp", seed=2**63)  # past a C++ long long: still the range, not a TypeError
    with pytest.raises(ValueError, match=r"threads is 1099511627776: must be in \[1, "):
        svmp.plan(fig35, "svmp", threads=2**40)
    with pytest.raises(ValueError, match="checker is 'gjk'"):
        svmp.plan(fig35, "svmp", checker="gjk")
    with pytest.raises(ValueError, match=r"q: expected shape \(2,\), got \(3,\)"):
        fig35.check([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"q\[0\] is nan"):
        fig35.is_valid([np.nan, 2.0])
    assert fig35.distance([3e200, 4e200], [0.0, 0.0]) == pytest.approx(5e200)  # no overflow to inf
    with pytest.raises(ValueError, match="seed is 3.5: expected an integer"):
        svmp.plan(fig35, "svmp", seed=3.5)
    with pytest.raises(ValueError, match=r"params\['prm.samples'\] = 100: planner 'prm' is not the planner run \('svmp'\)"):
        svmp.plan(fig35, "svmp", params={"prm.samples": 100})
    with pytest.raises(ValueError, match="path is None: expected a file name"):
        svmp.load_scenario(None)


def test_svm_smoothing_from_python(tmp_path):
    """simplify='svpp' is svmp-plan's --simplify svpp: on svpp_2d_01 (where it smooths, not keeps) the
    same waypoints as the driver's, certified and densely free, and not the shortcut's."""
    driver = os.environ.get("SVMP_PLAN", "")
    if not os.access(driver, os.X_OK):
        pytest.skip("SVMP_PLAN not set (run through ctest)")
    scenario = svmp.load_scenario(scenario_path("svpp_2d_01.yaml"))
    out = tmp_path / "p.json"
    subprocess.run([driver, "--scenario", scenario.path, "--planners", "svmp", "--simplify", "svpp", "--runs", "1",
                    "--paths", str(out)], check=True, capture_output=True)
    expected = np.array(json.loads(out.read_text())["runs"][0]["path"])
    smoothed = svmp.plan(scenario, "svmp", simplify="svpp")
    assert smoothed.solved and not smoothed.warnings
    np.testing.assert_array_equal(smoothed.path, expected)
    dense_recheck(scenario, smoothed.path, scenario.resolution / 10)
    assert not np.array_equal(smoothed.path, svmp.plan(scenario, "svmp", simplify=True).path)


def test_planners_lists_the_registry():
    names = svmp.planners()
    assert {"svmp", "prm", "local", "svpp"} <= set(names) and names == sorted(names)


def test_numpy_scalars_are_parameter_values(fig35):
    """np.float64(0.4) prints as 'np.float64(0.4)' under NumPy 2 and np.bool_ as 'True': both are read
    as the Python values they hold, the same run as with plain floats and bools."""
    plain = svmp.plan(fig35, "svmp", params={"sigma": 0.4, "step": 0.3})
    numpy = svmp.plan(fig35, "svmp", params={"sigma": np.float64(0.4), "step": np.float64(0.3)})
    assert plain.counters["collision_checks"] == numpy.counters["collision_checks"]
    np.testing.assert_array_equal(plain.path, numpy.path)
    assert svmp.plan(fig35, "prm", params={"samples": np.int64(100)}).status in ("solved", "failed")


def test_numpy_integers_are_seeds_queries_and_threads(fig35):
    """for seed in np.arange(...) plans as with Python integers (pybind11 alone refused np.int64)."""
    plain = svmp.plan(fig35, "svmp", seed=3, query=0, threads=1)
    numpy = svmp.plan(fig35, "svmp", seed=np.int64(3), query=np.int32(0), threads=np.uint8(1))
    assert plain.counters["collision_checks"] == numpy.counters["collision_checks"]
    np.testing.assert_array_equal(plain.path, numpy.path)
    assert svmp.load_scenario(pathlib.Path(fig35.path)).name == fig35.name


def test_a_scenario_planning_refuses_is_refused_here_too(tmp_path):
    """As svmp-plan: an obstacle's sample that misses its obstacle (plan() once trained on it)."""
    bad = tmp_path / "bad_sample.yaml"
    bad.write_text("robot: {type: point, bounds: {lower: [0, 0], upper: [1, 1]}}\n"
                   "obstacles: [{name: wall, shape: box, size: [0.2, 0.2, 1], position: [0.8, 0.8, 0], "
                   "sample: [0.5, 0.5]}]\nstart: [0.1, 0.1]\ngoal: [0.2, 0.2]\nresolution: 0.01\n")
    with pytest.raises(svmp.ScenarioError, match=r"obstacles\[0\]\.sample.*does not hit obstacle 'wall'"):
        svmp.plan(svmp.load_scenario(str(bad)), "prm")


def _plan_in_a_forked_child(path):
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        plan = svmp.plan(svmp.load_scenario(path), "prm", seed=3, threads=2)
    return plan.counters["collision_checks"], [str(w.message) for w in caught]


def test_a_process_forked_after_parallel_planning_plans_on_one_thread():
    """libgomp's threads do not survive fork(): a forked child that plans on several threads after the
    parent did would wait forever. It plans on one thread (the same counts) and warns."""
    import multiprocessing
    path = scenario_path("thesis_fig3_5.yaml")
    parent = svmp.plan(svmp.load_scenario(path), "prm", seed=3, threads=2)
    with multiprocessing.get_context("fork").Pool(1) as pool:
        result = pool.apply_async(_plan_in_a_forked_child, (path,))
        checks, messages = result.get(timeout=60)
    assert checks == parent.counters["collision_checks"]
    assert any("planning on 1 thread" in m for m in messages)


def test_a_proxy_that_did_not_converge_is_in_the_plans_warnings(fig35):
    """svmp-plan says it on stderr; the run's record (JSON, Plan.warnings) says it too."""
    plan = svmp.plan(fig35, "prm", checker="fastron-fk", params={"fastron-fk.max_updates": 1})
    assert any("fastron-fk stopped learning after 1 updates, not converged" in w for w in plan.warnings), plan.warnings
    assert not any("not converged" in w for w in svmp.plan(fig35, "prm", checker="fastron-fk").warnings)


def test_a_proxys_warnings_name_the_query_asked_for(tmp_path):
    """plan() runs a copy of the scenario holding the one query; its warnings still say which."""
    path = tmp_path / "two_queries.yaml"
    path.write_text(
        "robot: {type: point, bounds: {lower: [0, 0], upper: [10, 10]}}\n"
        "obstacles:\n"
        "  - {name: lower, shape: box, size: [4.0, 6.0, 1.0], position: [5.0, 3.0, 0]}\n"
        "  - {name: upper, shape: box, size: [4.0, 3.7, 1.0], position: [5.0, 8.15, 0]}\n"
        "queries:\n"
        "  - {start: [1.0, 9.5], goal: [9.0, 9.5]}\n"
        "  - {start: [1.0, 5.0], goal: [9.0, 5.0], witness: [[2.5, 6.15], [7.5, 6.15]]}\n"
        "resolution: 0.05\n")
    plan = svmp.plan(svmp.load_scenario(path), "prm", query=1, checker="fastron-fk", time_limit=2)
    assert any("along query 1's witness path" in w for w in plan.warnings), plan.warnings
    assert not any("query 0's" in w for w in plan.warnings), plan.warnings
