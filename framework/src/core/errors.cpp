#include "stochnav/core/errors.hpp"

namespace stochnav {

// Out-of-line destructors give each class one typeinfo across shared-library boundaries.
InputError::~InputError() = default;
ConfigError::~ConfigError() = default;
MissingDataError::~MissingDataError() = default;

}  // namespace stochnav
