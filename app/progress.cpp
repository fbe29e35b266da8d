#include "progress.h"

#include <ostream>
#include <unistd.h>

namespace phedra::cli {

Progress::Progress(std::ostream& out, std::string what, bool enabled)
    : out_(out), what_(std::move(what)), active_(enabled && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() { finish(); }

void Progress::update(std::size_t count) {
  if (!active_) return;
  out_ << "\r" << what_ << ": " << count << std::flush;
  shown_ = true;
}

void Progress::finish() {
  if (shown_) out_ << "\r\033[K" << std::flush;
  shown_ = false;
}

}  // namespace phedra::cli
