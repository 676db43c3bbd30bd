"""svmp.train and svmp.Model against NumPy: F is the sum over the exported support vectors, grad F
matches finite differences, the truncated evaluator sums exactly the terms inside its radius, train()
equals the C++ solver on the same data, and bad input raises ValueError naming the argument."""
import os
import subprocess
from decimal import Decimal

import numpy as np
import pytest

import svmp


def brute_force(model, Q, radius2=np.inf):
    """F and grad F at the rows of Q from the exported support vectors and coefficients."""
    diff = Q[:, None, :] - model.support_vectors[None, :, :]  # (n, m, d)
    d2 = (diff ** 2).sum(axis=2)
    terms = np.where(d2 < radius2, model.coefficients * np.exp(-model.gamma * d2), 0.0)
    F = terms.sum(axis=1) + model.bias
    grad = (-2 * model.gamma * terms[:, :, None] * diff).sum(axis=1)
    return F, grad


@pytest.fixture(scope="module")
def queries():
    return np.random.default_rng(3).uniform(-2.2, 2.2, (300, 2))


def test_model_exports_a_real_solution(model, two_rings):
    X, y = two_rings
    assert model.converged and 0 < len(model.coefficients) < len(X)
    assert model.support_vectors.shape == (len(model.coefficients), 2)
    np.testing.assert_array_equal(model.support_vectors, X[model.support_indices])
    alpha = model.alpha
    np.testing.assert_allclose(model.coefficients, y[model.support_indices] * alpha[model.support_indices])
    assert np.all((alpha >= 0) & (alpha <= 10.0 + 1e-12))
    assert abs(alpha @ y) < 1e-9  # the dual's equality constraint
    # It separates the rings: most training points on the right side.
    assert np.mean(np.sign(model.decision(X)) == y) > 0.95


def test_decision_is_the_sum_over_support_vectors(model, queries):
    F, _ = brute_force(model, queries)
    np.testing.assert_allclose(model.decision(queries), F, rtol=1e-12, atol=1e-12)
    assert model.decision(queries[5]) == pytest.approx(F[5], rel=1e-12, abs=1e-12)


def test_gradient_matches_finite_differences(model, queries):
    h = 1e-6
    grad = model.gradient(queries)
    assert grad.shape == queries.shape
    for k in range(2):
        step = np.zeros(2)
        step[k] = h
        central = (model.decision(queries + step) - model.decision(queries - step)) / (2 * h)
        np.testing.assert_allclose(grad[:, k], central, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(model.gradient(queries[7]), grad[7], rtol=1e-13)
    # A kernel so narrow that every term far from the samples is below e^-700: F is the bias and
    # grad F exactly zero there (it was 2 gamma e^-700 per term, about 1e-3 for a gamma of 1e300).
    narrow = svmp.train(np.array([[0.0, 0.0], [1.0, 0.0]]), np.array([1.0, -1.0]), C=1.0, gamma=1e300)
    np.testing.assert_array_equal(narrow.gradient(np.array([0.5, 0.5])), [0.0, 0.0])


def test_truncated_evaluator_sums_the_terms_inside_its_radius(model, queries):
    radius2 = 5.0 / model.gamma
    F, grad = brute_force(model, queries, radius2)
    np.testing.assert_allclose(model.decision(queries, truncated=True), F, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(model.gradient(queries, truncated=True), grad, rtol=1e-9, atol=1e-9)
    exact = model.decision(queries)
    gap = np.abs(model.decision(queries, truncated=True) - exact)
    assert np.all(gap <= model.truncation_bound + 1e-12)
    assert gap.max() > 0  # the truncation drops terms here, so the comparison above is not vacuous


def test_train_equals_the_cpp_solver(two_rings, tmp_path):
    reference = os.environ.get("SVMP_SOLVE_REFERENCE")
    if not reference:
        pytest.skip("SVMP_SOLVE_REFERENCE not set (run through ctest)")
    X, y = two_rings
    C = np.where(y > 0, 10.0, 4.0)  # per-sample bounds, as SVMP's class weights give
    samples = tmp_path / "samples.txt"
    with open(samples, "w") as f:
        f.write(f"{len(X)} 2 2.5 0.0001\n")
        for x, label, c in zip(X, y, C):
            f.write(f"{x[0]!r} {x[1]!r} {label!r} {c!r}\n")
    out = subprocess.run([reference, str(samples)], check=True, stdout=subprocess.PIPE, text=True).stdout.split()
    objective, bias, alpha = float(out[0]), float(out[1]), np.array([float(v) for v in out[2:]])
    model = svmp.train(X, y, C=C, gamma=2.5, eps=1e-4)
    np.testing.assert_array_equal(model.support_indices, np.flatnonzero(alpha > 0))
    assert model.objective == pytest.approx(objective, rel=1e-12)
    assert model.bias == pytest.approx(bias, rel=1e-12, abs=1e-12)
    np.testing.assert_allclose(model.alpha, alpha, rtol=1e-10, atol=1e-12)


def test_sigma_is_gamma_one_over_two_sigma_squared(two_rings):
    X, y = two_rings
    by_sigma, by_gamma = svmp.train(X, y, sigma=0.5), svmp.train(X, y, gamma=2.0)
    assert by_sigma.gamma == pytest.approx(2.0)
    np.testing.assert_allclose(by_sigma.alpha, by_gamma.alpha, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("kwargs, message", [
    ({"gamma": -1.0}, "gamma is -1"),
    ({"sigma": 0.0}, "sigma is 0"),
    ({"gamma": 1.0, "sigma": 1.0}, "give one of them"),
    ({"C": -2.0}, "C is -2"),
    ({"C": float("inf")}, "C is inf: must be positive and finite"),
    ({"gamma": "1"}, "gamma is '1': expected a real number"),
    ({"sigma": 1j}, "sigma is 1j: expected a real number"),
    ({"eps": None}, "eps is None: expected a real number"),
    ({"max_iterations": 2**63}, r"max_iterations is 9223372036854775808: must be in \[1, 2\^63 - 1\]"),
    ({"max_iterations": 1e6}, "max_iterations is 1000000.0: expected an integer"),
    ({"max_iterations": True}, "max_iterations is True: expected an integer"),
    ({"gamma": 10**400}, "gamma is 1000.*: out of a double's range"),
    ({"gamma": 1e308}, r"gamma is 1e\+308: must be positive and at most 1e300"),  # its gradient was NaN
    ({"gamma": np.bool_(True)}, "gamma is .*True.*: expected a real number"),
    ({"C": "2"}, "C is '2': give a positive number"),
    ({"C": True}, "C is True: give a positive number"),
    ({"shrinking": "no"}, "shrinking is 'no': expected True or False"),
    ({"shrinking": 1}, "shrinking is 1: expected True or False"),
])
def test_bad_parameters_raise_value_error(two_rings, kwargs, message):
    X, y = two_rings
    with pytest.raises(ValueError, match=message):
        svmp.train(X, y, **kwargs)


def test_bad_arrays_raise_value_error(two_rings, model):
    X, y = two_rings
    with pytest.raises(ValueError, match=r"X: expected shape \(n, d\), got \(160,\)"):
        svmp.train(X[:, 0], y)
    with pytest.raises(ValueError, match=r"y: expected shape \(160,\), got \(159,\)"):
        svmp.train(X, y[:-1])
    bad = X.copy()
    bad[4, 1] = np.nan
    with pytest.raises(ValueError, match=r"X\[4, 1\] is nan"):
        svmp.train(bad, y)
    with pytest.raises(ValueError, match=r"y\[0\] is 2"):
        svmp.train(X, np.where(y > 0, 2.0, -1.0))
    with pytest.raises(ValueError, match=r"x: expected shape \(n, 2\), got \(5, 3\)"):
        model.decision(np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"x\[1\] is inf"):
        model.gradient(np.array([0.0, np.inf]))
    with pytest.raises(ValueError, match="one class only|two classes|class"):
        svmp.train(X, np.ones(len(X)))
    with pytest.raises(ValueError, match="X: expected real numbers, got an array of complex numbers"):
        svmp.train(X + 1j, y)
    # Text and booleans are not numbers here, as they are not for the scalar arguments.
    with pytest.raises(ValueError, match="X: expected an array of numbers, got one of dtype <U"):
        svmp.train(X.astype(str), y)
    with pytest.raises(ValueError, match="y: expected an array of numbers, got one of dtype <U"):
        svmp.train(X, y.astype(str))
    with pytest.raises(ValueError, match="X: expected an array of numbers, got one of dtype bool"):
        svmp.train(X > 0, y)


def test_numbers_of_any_numeric_kind_are_arguments(two_rings):
    X, y = two_rings
    reference = svmp.train(X, y, C=2.0, gamma=0.5, eps=1e-3, max_iterations=100000)
    for kwargs in ({"gamma": np.float32(0.5), "max_iterations": np.int64(100000)},
                   {"gamma": np.array(0.5), "eps": np.array(1e-3), "max_iterations": np.array(100000)},
                   {"gamma": Decimal("0.5"), "C": np.float64(2.0)}):
        m = svmp.train(X, y, **{"C": 2.0, **kwargs})
        np.testing.assert_array_equal(m.alpha, reference.alpha)


def test_a_solve_stopped_by_its_iteration_limit_warns(two_rings):
    X, y = two_rings
    with pytest.warns(RuntimeWarning, match="stopped after 5 iterations"):
        m = svmp.train(X, y, C=1e6, gamma=10.0, max_iterations=5)
    assert not m.converged
    assert abs(m.alpha @ y) < 1e-9  # still feasible


def test_repr_gives_gamma_in_full():
    X = np.array([[0.0, 0.0], [1.0, 1.0]])
    assert "gamma=1e-07>" in repr(svmp.train(X, np.array([1.0, -1.0]), gamma=1e-7))
