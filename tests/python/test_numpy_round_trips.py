"""numpy in and out: arrays used in place or converted as documented, results as numpy arrays,
noise models through JSON and back, simulated records against their closed forms, fits that
recover the model they were simulated from."""

import json

import numpy as np
import pytest

import stochnav

GYRO_MODEL = {"units": "deg/h", "rate_hz": 100,
              "terms": [{"type": "angle_random_walk", "N": 0.05},
                        {"type": "rate_random_walk", "K": 3.0}]}


def gyro_record(seed=7, duration_s=6000.0):
    return stochnav.simulate_noise(GYRO_MODEL, duration_s, 100.0, seed)


def test_other_dtypes_and_strided_views_give_the_float64_result():
    y = np.random.default_rng(1).standard_normal(4096)
    reference = stochnav.allan(y, 10.0)
    as_float32 = y.astype(np.float32)
    np.testing.assert_array_equal(stochnav.allan(as_float32, 10.0).dev,
                                  stochnav.allan(as_float32.astype(np.float64), 10.0).dev)
    np.testing.assert_array_equal(stochnav.allan(list(y), 10.0).dev, reference.dev)
    both = np.empty(2 * y.size)
    both[::2] = y
    np.testing.assert_array_equal(stochnav.allan(both[::2], 10.0).dev, reference.dev)
    counts = np.arange(1000) % 7
    np.testing.assert_array_equal(stochnav.allan(counts, 1.0).dev,
                                  stochnav.allan(counts.astype(float), 1.0).dev)


def test_input_array_is_left_unchanged():
    y = np.random.default_rng(2).standard_normal(1000)
    before = y.copy()
    stochnav.allan(y, 1.0)
    stochnav.wv(y, 1.0)
    stochnav.davar(y, 1.0, 200, 100)
    np.testing.assert_array_equal(y, before)


def test_every_deviation_kind_and_tau_set_runs():
    y = np.random.default_rng(3).standard_normal(5000)
    for deviation in ("adev", "oadev", "mdev", "tdev", "hdev", "ohdev", "totdev"):
        for taus in ("octave", "decade", "dense", "all"):
            result = stochnav.allan(y, 1.0, deviation=deviation, taus=taus)
            assert result.deviation == deviation
            assert len(result) > 0 and np.all(result.lo <= result.dev)
            assert np.all(result.dev <= result.hi)


def test_phase_and_rate_input_agree():
    y = np.random.default_rng(4).standard_normal(10_000)
    phase = np.concatenate([[0.0], np.cumsum(y - y.mean())]) / 50.0
    from_rate = stochnav.allan(y, 50.0)
    from_phase = stochnav.allan(phase, 50.0, data="phase")
    np.testing.assert_array_equal(from_rate.m, from_phase.m)
    np.testing.assert_allclose(from_phase.dev, from_rate.dev, rtol=1e-9)


def test_davar_windows_equal_the_allan_deviation_of_each_window():
    y = np.random.default_rng(5).standard_normal(3000)
    result = stochnav.davar(y, 10.0, window=1000, step=500)
    assert result.dev.shape == (len(result.t), len(result.tau)) == (5, len(result.m))
    np.testing.assert_allclose(result.t, [50.0, 100.0, 150.0, 200.0, 250.0])
    for k in range(5):
        window = stochnav.allan(y[500 * k:500 * k + 1000], 10.0)
        np.testing.assert_allclose(result.dev[k], window.dev[:len(result.m)], rtol=1e-9)
    causal = stochnav.davar(y, 10.0, window=1000, step=500, causal=True)
    np.testing.assert_allclose(causal.t, result.t + 50.0)


def test_noise_model_json_round_trip_and_closed_forms():
    model = stochnav.NoiseModel.from_json(GYRO_MODEL)
    again = stochnav.NoiseModel.from_json(model.to_json())
    assert again.equals(model)
    assert model.units == "deg/h" and model.rate_hz == 100
    assert model.term_types == ["angle_random_walk", "rate_random_walk"]
    tau = np.array([1.0, 10.0, 100.0])
    expected = (60 * 0.05) ** 2 / tau + 3.0 ** 2 * tau / 10800
    np.testing.assert_allclose(model.allan_variance(tau), expected, rtol=1e-12)
    assert model.allan_deviation(10.0) == pytest.approx(np.sqrt(expected[1]), rel=1e-12)
    assert model.wavelet_variance(20.0) == pytest.approx(expected[1] / 2, rel=1e-12)
    assert model.diagnostics is None and not model.failed
    assert "angle_random_walk: N = 0.05 deg/sqrt(h)" in repr(model)


def test_simulated_record_matches_its_closed_form_within_the_interval():
    y = gyro_record()
    assert y.dtype == np.float64 and y.size == 600_000
    np.testing.assert_array_equal(y, gyro_record())  # same seed, same record
    result = stochnav.allan(y, 100.0)
    model = stochnav.NoiseModel.from_json(GYRO_MODEL)
    implied = model.allan_deviation(result.tau)
    inside = (result.lo <= implied) & (implied <= result.hi)
    assert inside.mean() >= 0.5  # 68.3 % intervals


def test_fit_recovers_the_simulated_model_and_round_trips_through_json():
    fitted = stochnav.fit(gyro_record(), 100.0, unit="deg/h")
    assert fitted.term_types == ["angle_random_walk", "rate_random_walk"]
    terms = {term["type"]: term for term in fitted.terms}
    for kind, name, truth in (("angle_random_walk", "N", 0.05), ("rate_random_walk", "K", 3.0)):
        value, sigma = terms[kind][name], terms[kind][name + "_sigma"]
        assert abs(value - truth) < 4 * sigma, (kind, value, sigma)
    assert fitted.diagnostics["automatic"] and not fitted.failed
    text = fitted.to_json()
    assert json.loads(text)["diagnostics"]["chosen_terms"] == fitted.term_types
    again = stochnav.NoiseModel.from_json(text)
    assert again.equals(fitted) and again.diagnostics == fitted.diagnostics
    assert "+/-" in repr(fitted)
    given = stochnav.fit(gyro_record(), 100.0, unit="deg/h",
                         terms="rate_random_walk,angle_random_walk")
    assert given.term_types == fitted.term_types and not given.diagnostics["automatic"]


def test_fit_equals_the_cli_fit_of_the_same_numbers(cli, tmp_path):
    y = gyro_record(seed=8, duration_s=2000.0)
    path = tmp_path / "gyro.csv"
    np.savetxt(path, y, header="gyro_deg_h", comments="", fmt="%.17g")
    done = cli("fit", "--input", path, "--rate", 100, "--unit", "deg/h", "--format", "json")
    assert done.returncode == 0, done.stderr
    from_cli = json.loads(done.stdout)
    from_python = stochnav.fit(y, 100.0, unit="deg/h").to_dict()
    assert from_python["terms"] == from_cli["terms"]
    assert from_python["diagnostics"]["chi_square"] == from_cli["diagnostics"]["chi_square"]


def test_allan_equals_the_cli_allan_of_the_same_numbers(cli, tmp_path):
    y = gyro_record(seed=9, duration_s=1000.0)
    path = tmp_path / "gyro.f64"
    y.astype("<f8").tofile(path)
    for deviation in ("oadev", "totdev"):
        done = cli("allan", "--input", path, "--rate", 100, "--deviation", deviation,
                   "--format", "json")
        assert done.returncode == 0, done.stderr
        from_cli = json.loads(done.stdout)
        result = stochnav.allan(y, 100.0, deviation=deviation)
        assert result.dev.tolist() == from_cli["adev"]
        assert result.lo.tolist() == from_cli["adev_lo"]
        assert result.n.tolist() == from_cli["n"] and result.alpha.tolist() == from_cli["alpha"]


def test_read_record_gives_the_file_values_as_numpy(tmp_path):
    path = tmp_path / "record.csv"
    path.write_text("t,gyro\n0,1.5\n0.01,2.5\n0.02,-1\n")
    record = stochnav.read_record(path, column="gyro", unit="deg/h")
    np.testing.assert_array_equal(record.values, [1.5, 2.5, -1.0])
    assert record.rate_hz == pytest.approx(100.0) and record.unit == "deg/h"
    assert stochnav.read_record(path, column=1).column == "gyro"
