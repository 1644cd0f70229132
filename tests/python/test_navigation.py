"""stochnav.simulate_scenario, run, Navigator and compare on a short drilling scenario (the
shipped drilling_short.json cut to 4 minutes): run from Python writes what `stochnav run` writes
on the same record; the Navigator stepped from Python follows run's navigation epoch by epoch;
compare returns results.json's contract."""

import json
import os

import numpy as np
import pytest

import stochnav
from conftest import REPOSITORY

RUN_CONFIG = json.loads((REPOSITORY / "configs/runs/drilling_build_hold.json").read_text())
del RUN_CONFIG["data"]


@pytest.fixture(scope="module")
def scenario(tmp_path_factory):
    """A 240-s drilling record: 60 s static, then 1-m stands with 20-s connections (ZUPT)."""
    config = json.loads((REPOSITORY / "configs/scenarios/drilling_short.json").read_text())
    drilling = config["drilling"]
    drilling.update(duration_s=240, initial_static_s=60, stand_length_m=1.0, connection_s=20,
                    vibration_episodes=[])
    out = tmp_path_factory.mktemp("scenario") / "drilling"
    assert stochnav.simulate_scenario(config, out) == str(out)
    for name in ("imu.csv", "truth.csv", "aids.csv", "scenario.json"):
        assert (out / name).exists()
    return out


def start_from_truth(folder):
    """An initial_state at the truth's first row, so that run and Navigator start alike."""
    truth = stochnav._navigation.read_columns(folder / "truth.csv")
    return {"tie_on": {"latitude_deg": truth["lat"][0], "longitude_deg": truth["lon"][0],
                       "height_m": truth["h"][0]},
            "attitude": {"inclination_deg": truth["inclination"][0],
                         "azimuth_deg": truth["azimuth"][0],
                         "toolface_deg": truth["toolface"][0]}}


def test_run_writes_what_the_cli_writes(scenario, tmp_path, cli):
    config_path = tmp_path / "run.json"
    config_path.write_text(json.dumps(RUN_CONFIG))
    done = cli("run", config_path, "--data", scenario, "--out", tmp_path / "cli", "--no-plot")
    assert done.returncode == 0, done.stderr
    result = stochnav.run(RUN_CONFIG, data=scenario, out=tmp_path / "python")
    for name in ("nav.csv", "biases.csv", "covariance.csv", "innovations.csv", "errors.csv",
                 "survey.csv"):
        assert (tmp_path / "python" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    cli_metrics = json.loads((tmp_path / "cli" / "metrics.json").read_text())
    assert result.metrics["metrics"] == cli_metrics["metrics"]
    assert result.metrics["consistency"] == cli_metrics["consistency"]
    # The tables as numpy columns, equal to the files.
    navigation = stochnav._navigation.read_columns(tmp_path / "cli" / "nav.csv")
    assert result.navigation.keys() == navigation.keys()
    for name, column in navigation.items():
        np.testing.assert_array_equal(result.navigation[name], column)
    assert result.errors is not None and result.survey["md_m"].size >= 1
    assert result.innovations["accepted"].size == len(
        (tmp_path / "cli" / "innovations.csv").read_text().splitlines()) - 1
    assert result.epochs == 24_000 and result.filter_ok
    assert "max |error|" in repr(result)
    # Without out: a temporary folder, the same numbers.
    again = stochnav.run(RUN_CONFIG, data=scenario)
    assert again.out is None
    np.testing.assert_array_equal(again.navigation["lat"], result.navigation["lat"])


def imu_increments(folder):
    imu = stochnav._navigation.read_columns(folder / "imu.csv")
    t = imu["t"]
    start = t[0] - (t[1] - t[0])  # the reader's start: one interval before the first row
    dtheta = np.column_stack([imu["dtheta_x"], imu["dtheta_y"], imu["dtheta_z"]])
    dv = np.column_stack([imu["dv_x"], imu["dv_y"], imu["dv_z"]])
    return start, t, dtheta, dv


def test_navigator_follows_run_epoch_by_epoch(scenario, tmp_path):
    config = dict(RUN_CONFIG, initial_state=start_from_truth(scenario))
    result = stochnav.run(config, data=scenario, out=tmp_path / "run")
    start, t, dtheta, dv = imu_increments(scenario)
    navigator = stochnav.Navigator(config, aid_data=scenario / "aids.csv", imu_rate_hz=100.0,
                                   t0_s=start)
    assert [name for name, _, _ in navigator.layout()][:5] == [
        "position", "velocity", "attitude", "accel_bias", "gyro_bias"]
    decimation = config["output"]["decimation"]
    nav = result.navigation
    innovations = 0
    # Blocks of one output interval through steps(), the first epochs through step().
    first = navigator.step(t[0], t[0] - start, dtheta[0], dv[0])
    innovations += first["t"].size
    for row in range(len(nav["t"])):
        end = (row + 1) * decimation
        begin = max(1, row * decimation)
        innovations += navigator.steps(t[begin:end], dtheta[begin:end], dv[begin:end])["t"].size
        state = navigator.state()
        assert state["t_s"] == pytest.approx(nav["t"][row], abs=5e-4)
        assert state["latitude_deg"] == pytest.approx(nav["lat"][row], abs=1e-9)
        assert state["longitude_deg"] == pytest.approx(nav["lon"][row], abs=1e-9)
        assert state["height_m"] == pytest.approx(nav["h"][row], abs=1e-4)
        np.testing.assert_allclose(state["v_n"], [nav["ve"][row], nav["vn"][row], nav["vu"][row]],
                                   rtol=1e-5, atol=1e-12)
        assert state["inclination_deg"] == pytest.approx(nav["inclination"][row], abs=1e-6)
    assert navigator.epochs == result.epochs
    assert innovations == result.innovations["t"].size
    assert navigator.health()["ok"]
    p = navigator.covariance()
    assert p.shape == (navigator.layout()[-1][1] + navigator.layout()[-1][2],) * 2
    np.testing.assert_allclose(p, p.T, atol=1e-12 * np.abs(p).max())
    # Every block by name: the biases as state() gives them, the covariance's blocks.
    for name, offset, size in navigator.layout():
        np.testing.assert_array_equal(navigator.block_covariance(name),
                                      p[offset:offset + size, offset:offset + size])
    np.testing.assert_allclose(navigator.block_estimate("gyro_bias") / (np.pi / 180 / 3600),
                               navigator.state()["gyro_bias_deg_h"], rtol=1e-12)
    assert navigator.block_estimate("gyro_scale_factor").shape == (3,)
    with pytest.raises(ValueError, match="navigation block"):
        navigator.block_estimate("attitude")
    with pytest.raises(ValueError, match="no state block 'gyro.nothing'"):
        navigator.block_covariance("gyro.nothing")
    now = navigator.covariance(now=True)
    assert now.shape == p.shape


def test_navigator_refuses_bad_increments_and_a_start_without_attitude():
    config = dict(RUN_CONFIG, aids=[], initial_state={
        "tie_on": {"latitude_deg": 40, "longitude_deg": 116, "height_m": 50},
        "attitude": {"inclination_deg": 10, "azimuth_deg": 30, "toolface_deg": 0}})
    navigator = stochnav.Navigator(config, imu_rate_hz=100.0)
    with pytest.raises(stochnav.InputError, match="dt > 0"):
        navigator.step(0.01, 0.0, [0, 0, 0], [0, 0, 0])
    with pytest.raises(stochnav.InputError, match="finite"):
        navigator.step(0.01, 0.01, [np.nan, 0, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="expected 3 values"):
        navigator.step(0.01, 0.01, [0, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="shape"):
        navigator.steps(np.array([0.01, 0.02]), np.zeros((2, 2)), np.zeros((2, 3)))
    navigator.step(0.01, 0.01, [0, 0, 0], [0, 0, 0.098])
    assert navigator.epochs == 1
    aligned = dict(config, initial_state={
        "tie_on": {"latitude_deg": 40, "longitude_deg": 116, "height_m": 50},
        "alignment": {"static_s": 60}})
    with pytest.raises(stochnav.ConfigError, match="/initial_state/attitude"):
        stochnav.Navigator(aligned)
    with pytest.raises(stochnav.ConfigError, match="/noise/gyro/plugin"):
        stochnav.Navigator(dict(config, noise={"gyro": {"plugin": "no_such_model"},
                                               "accel": config["noise"]["accel"]}))


def test_compare_returns_the_results_contract(scenario, tmp_path):
    experiment = {
        "data": {"scenario": str(scenario)},
        "baseline": "white",
        "aids": RUN_CONFIG["aids"],
        "filter": RUN_CONFIG["filter"],
        "variants": [
            {"name": "white", "noise": RUN_CONFIG["noise"]},
            {"name": "white_small",
             "noise": {"gyro": {"plugin": "white", "params": {"N": 2e-3, "K": 1.0}},
                       "accel": RUN_CONFIG["noise"]["accel"]}},
        ],
    }
    result = stochnav.compare(experiment, out=tmp_path / "compare")
    variants = result.results["variants"]
    assert [v["name"] for v in variants] == ["white", "white_small"]
    for variant in variants:
        assert "fitted" in variant and "consistency" in variant
        assert {"nees_mean", "nees_bounds", "inside_3sigma"} <= variant["consistency"].keys()
    assert "pairs" in result.results
    assert (tmp_path / "compare" / "results.json").exists()
    assert "white_small" in result.table
    with pytest.raises(stochnav.ConfigError, match="seeds"):
        stochnav.compare(experiment, seeds=[1, 2])
