#pragma once
// A one-line progress display on a terminal (none when standard error is not a
// TTY, or when disabled).

#include <iosfwd>
#include <string>

namespace phedra::cli {

class Progress {
 public:
  Progress(std::ostream& out, std::string what, bool enabled);
  ~Progress();
  void update(std::size_t count);
  void finish();

 private:
  std::ostream& out_;
  std::string what_;
  bool active_;
  bool shown_ = false;
};

}  // namespace phedra::cli
