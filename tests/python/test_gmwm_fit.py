"""stochnav.fit(..., method="gmwm"): the same fit as `stochnav fit --method gmwm` on the same
numbers (the JSON documents equal), a known white noise recovered, and the ADIS16405 headline
case (the white noise on its bound dropped, the refit passing)."""

import json

import numpy as np

import stochnav
from conftest import require_shared_file

TERMS = ["angle_random_walk", "rate_random_walk"]


def white_and_walk(n=1 << 16, seed=5):
    """White noise N = 1e-3 plus a random walk K = 2e-4, plain units at 100 Hz."""
    rng = np.random.default_rng(seed)
    return 1e-2 * rng.standard_normal(n) + np.cumsum(2e-5 * rng.standard_normal(n))


def test_equals_the_cli_fit(cli, tmp_path):
    y = white_and_walk()
    path = tmp_path / "record.txt"
    np.savetxt(path, y, fmt="%.17g")
    fitted = stochnav.fit(y, 100.0, terms=TERMS, method="gmwm")
    run = cli("fit", "--method", "gmwm", "--input", path, "--rate", "100", "--terms",
              ",".join(TERMS), "--format", "json")
    assert run.returncode == 0, run.stderr
    assert json.loads(fitted.to_json()) == json.loads(run.stdout)
    assert fitted.diagnostics["j_test"]["dof"] > 0
    n = fitted.terms[0]
    assert n["type"] == "angle_random_walk"
    assert abs(n["N"] / 1e-3 - 1.0) < 0.05


def test_adis_white_noise_is_dropped_and_the_refit_passes():
    record = stochnav.read_record(
        require_shared_file("imu-static/adis16405_imu1_static_100hz.csv"), column="gyro_x_dps",
        unit="deg/s")
    fitted = stochnav.fit(record.values, record.rate_hz, unit="deg/s", method="gmwm",
                          terms=["angle_random_walk", "gauss_markov", "rate_random_walk"])
    assert not fitted.failed
    assert [t["type"] for t in fitted.terms] == ["gauss_markov", "rate_random_walk"]
    assert fitted.diagnostics["dropped_terms"][0].startswith("angle_random_walk")
    assert fitted.diagnostics["j_test"]["p_value"] > 0.01


def test_steering_equals_the_cli_with_either_method(cli, tmp_path):
    """start, fix and bound reach both methods as the CLI's options do: the terms of
    `stochnav fit --fix ... --bound ...`, the fixed value held exactly (sigma 0)."""
    y = white_and_walk()
    path = tmp_path / "record.txt"
    np.savetxt(path, y, fmt="%.17g")
    for method in ("avar", "gmwm"):
        fitted = stochnav.fit(y, 100.0, terms=TERMS, method=method,
                              fix="rate_random_walk.K=2e-4", bound="angle_random_walk.N=1e-4:1e-2")
        run = cli("fit", "--method", method, "--input", path, "--rate", "100", "--terms",
                  ",".join(TERMS), "--fix", "rate_random_walk.K=2e-4",
                  "--bound", "angle_random_walk.N=1e-4:1e-2", "--format", "json")
        assert run.returncode == 0, run.stderr
        # The CLI integrates the text record as it reads it: equal to rounding.
        expected = json.loads(run.stdout)["terms"]
        assert [t["type"] for t in fitted.terms] == [t["type"] for t in expected]
        for term, cli_term in zip(fitted.terms, expected):
            for key, value in cli_term.items():
                if isinstance(value, float):
                    assert abs(term[key] - value) <= 1e-9 * abs(value), (method, key)
        k = fitted.terms[1]
        assert k["type"] == "rate_random_walk" and k["K"] == 2e-4 and k["K_sigma"] == 0


def test_steering_needs_the_terms():
    try:
        stochnav.fit(white_and_walk(), 100.0, fix="rate_random_walk.K=2e-4")
    except stochnav.ConfigError as error:
        assert "terms" in str(error)
    else:
        raise AssertionError("steering without terms was accepted")
