"""Every stochnav input error is a ValueError (stochnav.InputError or stochnav.ConfigError)
with the library's one-line message, the same line the CLI prints after "stochnav: error: ";
wrong dtype, shape, NaN or a strided array raise or convert, never crash."""

import json

import numpy as np
import pytest

import stochnav

WHITE = {"units": "deg/h", "rate_hz": 100, "terms": [{"type": "angle_random_walk", "N": 0.05}]}


def cli_message(done):
    assert done.returncode == 2, done.stderr
    line = done.stderr.strip()
    assert "\n" not in line and line.startswith("stochnav: error: ")
    return line[len("stochnav: error: "):]


@pytest.mark.parametrize("bad, fragment", [
    (np.array([1.0, 2.0, np.nan, 4.0] * 10), "x[2] is nan"),
    (np.array([1.0, np.inf] * 10), "x[1] is infinite"),
    (np.array([3.0]), "x: 1 sample(s); at least 2 are needed"),
])
def test_bad_samples_are_input_errors_naming_the_index(bad, fragment):
    for call in (lambda: stochnav.allan(bad, 1.0), lambda: stochnav.wv(bad, 1.0),
                 lambda: stochnav.fit(bad, 1.0), lambda: stochnav.davar(bad, 1.0, 4, 1)):
        with pytest.raises(stochnav.InputError) as error:
            call()
        assert isinstance(error.value, ValueError)
        assert fragment in str(error.value)
        assert "\n" not in str(error.value)


@pytest.mark.parametrize("bad, fragment", [
    (np.zeros((10, 3)), "shape (10, 3) is not 1-D"),
    (np.zeros(10, dtype=complex), "dtype complex128 is not real numbers"),
    (np.array(["a", "b"]), "is not real numbers"),
    (np.array([object(), object()]), "is not real numbers"),
    (np.float64(3.0), "shape () is not 1-D"),
])
def test_wrong_shapes_and_dtypes_are_value_errors(bad, fragment):
    with pytest.raises(ValueError) as error:
        stochnav.allan(bad, 1.0)
    assert fragment in str(error.value)


def test_too_short_records_say_so():
    with pytest.raises(stochnav.InputError, match="too few for any oadev averaging time"):
        stochnav.allan(np.arange(3.0), 1.0)
    with pytest.raises(stochnav.InputError, match="wv needs at least 3"):
        stochnav.wv(np.arange(10.0), 1.0)
    with pytest.raises(stochnav.InputError, match="rate is constant"):
        stochnav.wv(np.ones(100), 1.0)


def test_bad_arguments_are_config_errors():
    y = np.random.default_rng(1).standard_normal(100)
    cases = [
        (lambda: stochnav.allan(y, 1.0, taus="weekly"), "taus 'weekly': use octave"),
        (lambda: stochnav.allan(y, 1.0, data="angle"), "data 'angle': use \"rate\""),
        (lambda: stochnav.allan(y, -1.0), "rate -1 Hz"),
        (lambda: stochnav.allan(y, float("nan")), "rate nan Hz"),
        (lambda: stochnav.fit(y, 1.0, terms=["pink"]), "terms: unknown term 'pink'"),
        (lambda: stochnav.fit(y, 1.0, terms=[]), "terms: no term named"),
        (lambda: stochnav.fit(y, 1.0, taus="all"), "use octave, decade or dense for a fit"),
        (lambda: stochnav.fit(y, 1.0, method="wavelets"), "method 'wavelets'"),
        (lambda: stochnav.fit(y, 1.0, method="gmwm"), "terms: method=\"gmwm\" needs the terms"),
        (lambda: stochnav.fit(y, 1.0, robust=True), "pass method=\"gmwm\""),
        (lambda: stochnav.fit(y, 1.0, terms="angle_random_walk", method="gmwm",
                              gauss_markov_sampling="midpoint"),
         "gauss_markov_sampling 'midpoint'"),
        (lambda: stochnav.fit(y, 1.0, unit="furlong"), "unit: unknown unit 'furlong'"),
        (lambda: stochnav.davar(y, 1.0, window=0, step=1), "window 0: give a whole number"),
        (lambda: stochnav.davar(y, 1.0, window=200, step=1), "longer than the record"),
        (lambda: stochnav.simulate_noise(WHITE, 10, 100, -1), "seed -1"),
        (lambda: stochnav.simulate_noise(WHITE, -10, 100, 1), "duration_s must be"),
        (lambda: stochnav.diagnose(y, 1.0, WHITE, unit="m/s^2"), "the model is in deg/h"),
        (lambda: stochnav.NoiseModel.from_json({"units": "deg/h"}), "rate_hz"),
    ]
    for call, fragment in cases:
        with pytest.raises(stochnav.ConfigError) as error:
            call()
        assert fragment in str(error.value), str(error.value)
        assert isinstance(error.value, ValueError)


def test_messages_are_the_cli_messages(cli, tmp_path):
    y = np.random.default_rng(2).standard_normal(200)
    record = tmp_path / "record.txt"
    np.savetxt(record, y)
    # An unknown deviation: the library's parse_deviation.
    with pytest.raises(stochnav.ConfigError) as error:
        stochnav.allan(y, 1.0, deviation="xdev")
    assert str(error.value) == cli_message(
        cli("allan", "--input", record, "--rate", 1, "--deviation", "xdev"))
    # A bad noise model file: noise_model_from_json's pointer and form, prefixed by the file.
    model = tmp_path / "model.json"
    model.write_text(json.dumps({"units": "deg/h", "rate_hz": 100,
                                 "terms": [{"type": "angle_random_walk", "N": -1}]}))
    with pytest.raises(stochnav.ConfigError) as error:
        stochnav.simulate_noise(str(model), 10.0, 100.0, 1)
    assert str(error.value) == cli_message(
        cli("simulate", "noise", "--model", model, "--duration", 10, "--rate", 100, "--seed", 1,
            "--out", tmp_path / "out.csv"))
    # A bad run config: parse_run_config's pointer.
    config = tmp_path / "run.json"
    config.write_text(json.dumps({"data": {"imu": "imu.csv"}, "noise": {}}))
    (tmp_path / "imu.csv").write_text("t,gyro_x\n")
    with pytest.raises(stochnav.ConfigError) as error:
        stochnav.run(str(config))
    assert str(error.value) == cli_message(cli("run", config, "--out", tmp_path / "run"))
    # A record file that is not numbers: the reader's file and line.
    bad = tmp_path / "bad.txt"
    bad.write_text("1.0\n2.0\nthree\n")
    with pytest.raises(stochnav.InputError) as error:
        stochnav.read_record(str(bad), rate=1.0)
    assert str(error.value) == cli_message(cli("allan", "--input", bad, "--rate", 1))


def test_a_failed_fit_raises_unless_kept():
    # A strong rate random walk that a white-noise-only model cannot explain: chi-square fails.
    model = {"units": "deg/h", "rate_hz": 100,
             "terms": [{"type": "angle_random_walk", "N": 0.05},
                       {"type": "rate_random_walk", "K": 5.0}]}
    y = stochnav.simulate_noise(model, 3000.0, 100.0, 4)
    with pytest.raises(stochnav.InputError, match="fit failed"):
        stochnav.fit(y, 100.0, unit="deg/h", terms=["angle_random_walk"])
    kept = stochnav.fit(y, 100.0, unit="deg/h", terms=["angle_random_walk"], keep_failed=True)
    assert kept.failed and kept.diagnostics["failure"]
    with pytest.raises(stochnav.ConfigError, match="a failed fit"):
        stochnav.simulate_noise(kept, 10.0, 100.0, 1)
    assert stochnav.simulate_noise(kept, 10.0, 100.0, 1, accept_failed=True).size == 1000
