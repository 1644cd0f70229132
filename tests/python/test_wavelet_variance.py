"""stochnav.wv against the R package wv's table of the ADIS16405 record (../shared/data/gmwm,
SOURCES.md there) at the C++ suite's tolerances (tests/stats/wavelet_variance_test.cpp): every
channel and scale, wv and its 95 % interval to 1e-8 relative, scales to 1e-12; and the
estimator's relations to the Allan variance and to phase input."""

import csv

import numpy as np
import pytest

import stochnav
from conftest import require_shared_file

# The ADIS16405 column of each channel of adis_wv_ref.csv.
CHANNEL_COLUMNS = {"Gyro. X": "gyro_x_dps", "Gyro. Y": "gyro_y_dps", "Gyro. Z": "gyro_z_dps",
                   "Accel. X": "acc_x_g", "Accel. Y": "acc_y_g", "Accel. Z": "acc_z_g"}


def reference_rows():
    rows = {}
    with open(require_shared_file("gmwm/adis_wv_ref.csv"), newline="") as table:
        for row in csv.DictReader(table):
            rows.setdefault(row["channel"], []).append(
                [float(row[k]) for k in ("scale_s", "wv", "ci_low", "ci_high")])
    return {channel: np.array(values) for channel, values in rows.items()}


def relative(a, b):
    return np.abs(a - b) / np.abs(b)


@pytest.mark.parametrize("channel", sorted(CHANNEL_COLUMNS))
def test_matches_the_wv_package_on_every_adis_scale(channel):
    reference = reference_rows()[channel]
    record = stochnav.read_record(
        require_shared_file("imu-static/adis16405_imu1_static_100hz.csv"),
        column=CHANNEL_COLUMNS[channel])
    assert len(record) == 1_000_000
    result = stochnav.wv(record.values, record.rate_hz)
    assert len(result) == len(reference) == 18
    np.testing.assert_array_equal(result.scale, 2 ** np.arange(1, 19))
    np.testing.assert_array_equal(result.n, 1_000_000 - result.scale + 1)
    assert relative(result.scale_s, reference[:, 0]).max() < 1e-12
    assert relative(result.wv, reference[:, 1]).max() < 1e-8
    assert relative(result.lo, reference[:, 2]).max() < 1e-8
    assert relative(result.hi, reference[:, 3]).max() < 1e-8


def white_noise(samples=1 << 14, seed=3):
    return np.random.default_rng(seed).standard_normal(samples)


def test_is_half_the_overlapping_allan_variance_at_half_the_scale():
    y = white_noise()
    result = stochnav.wv(y, 2.0)
    allan = stochnav.allan(y, 2.0, taus="octave")
    compared = 0
    for level, variance in zip(result.level, result.wv):
        adev = allan.dev[allan.m == 2 ** (level - 1)]
        if adev.size:  # the octave OADEV set stops before the largest scales
            assert variance == pytest.approx(adev[0] ** 2 / 2, rel=1e-12)
            compared += 1
    assert compared >= 10


def test_phase_input_gives_the_rate_input_result():
    y = white_noise()
    phase = np.concatenate([[0.0], np.cumsum(y) / 2.0])
    from_rate = stochnav.wv(y, 2.0)
    from_phase = stochnav.wv(phase, 2.0, data="phase")
    np.testing.assert_allclose(from_phase.wv, from_rate.wv, rtol=1e-9)


def test_robust_estimate_resists_outliers_and_keeps_its_interval_around_it():
    y = white_noise()
    y[::500] = 50.0
    classical = stochnav.wv(y, 1.0)
    robust = stochnav.wv(y, 1.0, robust=True)
    assert robust.robust and not classical.robust
    assert robust.wv[0] < 0.5 * classical.wv[0]
    assert robust.wv[0] == pytest.approx(0.5, rel=0.1)  # the clean white noise's level-1 wv
    assert np.all(robust.lo < robust.wv) and np.all(robust.wv < robust.hi)
    assert "robust, efficiency 0.6" in repr(robust)
