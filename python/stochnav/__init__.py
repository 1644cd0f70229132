"""stochnav: inertial-sensor noise modelling for Kalman filters, from numpy.

The library behind the ``stochnav`` command-line tool, on arrays: every function calls the same
library code as the CLI subcommand of the same name, so the numbers agree with it.

Statistics (numpy float64 in, result objects with numpy arrays out)
    allan(x, rate, deviation="oadev", taus="octave", data="rate")  -> AllanResult
    davar(x, rate, window, step, causal=False)                      -> DavarResult
    wv(x, rate, robust=False)                                       -> WvResult
    read_record(path, column=None, rate=None)                       -> Record
Noise models
    fit(x, rate, terms=None, method="avar", unit="plain", ...)      -> NoiseModel
    NoiseModel.from_json(text or dict), NoiseModel.load(path), .to_json(), .terms,
    .diagnostics, .allan_variance(tau), .wavelet_variance(scale_s)
    simulate_noise(model, duration_s, rate_hz, seed)                -> numpy array
    diagnose(x, rate, model)                                        -> report dict
Navigation (configs as dicts or file paths, as in configs/)
    simulate_scenario(config, out)                                  -> output folder
    run(config, data=None, out=None)                                -> RunResult
    compare(experiment, seeds=None, out=None)                       -> CompareResult
    Navigator(config, aid_data=None, imu_rate_hz=100)               step-by-step filter
Errors
    InputError, ConfigError: the library's one-line messages; both are ValueError.

Units: rates in any unit U with ``unit=`` naming it for fits (deg/h, deg/s, rad/s, m/s^2, g,
plain); tau and times in s; rates in Hz. docs/python.md has the details.
"""

from ._stochnav import (
    __version__,
    AllanResult,
    ConfigError,
    DavarResult,
    InputError,
    Navigator,
    NoiseModel,
    Record,
    WvResult,
    allan,
    davar,
    diagnose,
    fit,
    read_record,
    simulate_noise,
    simulate_scenario,
    wv,
)
from ._navigation import CompareResult, RunResult, compare, run

# Shown as stochnav.X (help(), repr, tracebacks), not as the compiled module's.
for _name in ("AllanResult", "ConfigError", "DavarResult", "InputError", "Navigator", "NoiseModel",
              "Record", "WvResult"):
    globals()[_name].__module__ = __name__
del _name

__all__ = [
    "AllanResult", "CompareResult", "ConfigError", "DavarResult", "InputError", "Navigator",
    "NoiseModel", "Record", "RunResult", "WvResult", "allan", "compare", "davar", "diagnose",
    "fit", "read_record", "run", "simulate_noise", "simulate_scenario", "wv",
]
