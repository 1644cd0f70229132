#pragma once
// stochnav.NoiseModel: a noise model (model/noise_model.hpp) with the JSON it came from, so a
// fit's 1-sigma uncertainties and diagnostics travel with it (fit/fit_result_json.hpp).

#include "pybind.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "stochnav/model/noise_model.hpp"

namespace stochnav::python {

struct PythonNoiseModel {
  NoiseModel model;            ///< natural units
  nlohmann::json document;     ///< the model's JSON in reporting units (a fit's: with sigmas)
  std::vector<NoiseTerm> sigma;  ///< a fit's 1-sigma per term (natural units); empty otherwise

  /// True when the document's diagnostics flag a failed fit ("diagnostics": {"failed": true}).
  bool failed() const;
  /// Why (diagnostics.failure), or "" when not failed.
  std::string failure() const;
};

/// A model from its JSON (the DESIGN.md noise model, or `stochnav fit --format json`), checked
/// by noise_model_from_json; `source` prefixes its ConfigError messages (a file name) when
/// not empty.
PythonNoiseModel noise_model_from_document(const nlohmann::json& document,
                                           const std::string& source);

/// A model argument: a stochnav.NoiseModel, a dict, or the path of a JSON file. `what` names the
/// argument in messages ("model").
PythonNoiseModel noise_model_argument(const py::handle& object, const std::string& what);

}  // namespace stochnav::python
