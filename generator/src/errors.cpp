#include "phedra/errors.h"

#include "phedra/number_format.h"

namespace phedra {

InvalidInputError::InvalidInputError(std::string field, const std::string& message)
    : Error(ExitCode::bad_input, field.empty() ? message : field + ": " + message),
      field_(std::move(field)),
      reason_(message) {}

OutOfIntervalError::OutOfIntervalError(double t, double lo, double hi)
    : InvalidInputError("t", "t = " + format_number(t) + " is outside the flexion interval [" +
                                 format_number(lo) + ", " + format_number(hi) + "]") {}

}  // namespace phedra
