#include "progress.h"

#include <algorithm>
#include <ostream>
#include <unistd.h>

namespace phedra::cli {

Progress::Progress(std::ostream& out, std::string what, bool enabled)
    : out_(out), what_(std::move(what)), active_(enabled && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() { finish(); }

void Progress::update(double fraction, const std::string& detail) {
  if (!active_) return;
  const int width = 30;
  const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * width + 0.5);
  out_ << "\r" << what_ << " [" << std::string(filled, '#') << std::string(width - filled, '-') << "] "
       << static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100 + 0.5) << "%  " << detail << "\033[K" << std::flush;
  shown_ = true;
}

void Progress::finish() {
  if (shown_) out_ << "\r\033[K" << std::flush;
  shown_ = false;
}

}  // namespace phedra::cli
