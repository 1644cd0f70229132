"""stochnav.diagnose: report.json's contract from an array; an already consistent model gives no
iterations, a model missing its rate random walk gets it named and added."""

import pytest

import stochnav

WHITE = {"units": "deg/h", "rate_hz": 100, "terms": [{"type": "angle_random_walk", "N": 0.05}]}
WALK = {"units": "deg/h", "rate_hz": 100,
        "terms": [{"type": "angle_random_walk", "N": 0.05},
                  {"type": "rate_random_walk", "K": 2.0}]}


def test_a_consistent_model_needs_no_iteration():
    y = stochnav.simulate_noise(WHITE, 2000.0, 100.0, 5)
    report = stochnav.diagnose(y, 100.0, WHITE, seeds=0)
    assert report["consistent"] and report["iterations"] == []
    assert {"gap_initial", "gap_final", "final_model"} <= report.keys()


def test_a_missing_rate_random_walk_is_named_and_added():
    y = stochnav.simulate_noise(WALK, 4000.0, 100.0, 6)
    report = stochnav.diagnose(y, 100.0, stochnav.NoiseModel.from_json(WHITE), seeds=0)
    effects = [step["effect"] for step in report["iterations"]]
    assert "rate_random_walk" in effects
    assert report["gap_final"] < report["gap_initial"]
    final = stochnav.NoiseModel.from_json(report["final_model"])
    assert "rate_random_walk" in final.term_types
