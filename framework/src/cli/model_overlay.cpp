#include "model_overlay.hpp"

namespace stochnav::cli {

ModelOverlay model_overlay(const std::string&, const Record&, double, double) { return {}; }

}  // namespace stochnav::cli
