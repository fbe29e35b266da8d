#pragma once
// Typed exceptions. The command catches them, prints one line and exits with
// the code of the error (see docs/cli.md, "Exit codes").

#include <stdexcept>
#include <string>

namespace phedra {

/// Exit codes of the `phedra` command, one per kind of outcome.
enum class ExitCode : int {
  ok = 0,            ///< success
  check_failed = 1,  ///< a check ran and found a value above tolerance
  bad_input = 2,     ///< a preset, option or parameter violates an assumption
  io = 3,            ///< a file could not be read or written
  internal = 4,      ///< a bug: please report it
};

/// Base of every phedra error.
class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode exit_code() const { return code_; }

 private:
  ExitCode code_;
};

/// A violated precondition of the input. `field()` names the offending preset
/// field with its index (for example "directions[3]"), empty when the error
/// concerns the input as a whole; what() is "field: message".
class InvalidInputError : public Error {
 public:
  InvalidInputError(std::string field, const std::string& message);
  const std::string& field() const { return field_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string field_;
  std::string reason_;
};

/// A motion parameter outside the flexion interval (an input error, exit 2).
class OutOfIntervalError : public InvalidInputError {
 public:
  OutOfIntervalError(double t, double lo, double hi);
};

/// A file that cannot be read or written.
class IOError : public Error {
 public:
  explicit IOError(const std::string& message) : Error(ExitCode::io, message) {}
};

}  // namespace phedra
