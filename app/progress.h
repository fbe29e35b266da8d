#pragma once
// A one-line progress bar on a terminal (none when standard error is not a
// TTY, or when disabled).

#include <iosfwd>
#include <string>

namespace phedra::cli {

class Progress {
 public:
  Progress(std::ostream& out, std::string what, bool enabled);
  ~Progress();
  /// Draws `what [#####-----]  50%  detail`.
  void update(double fraction, const std::string& detail);
  void finish();

 private:
  std::ostream& out_;
  std::string what_;
  bool active_;
  bool shown_ = false;
};

}  // namespace phedra::cli
