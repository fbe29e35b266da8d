#include "phedra/closed_profile.h"

#include <algorithm>

namespace phedra {

bool has_closed_profile(const ControlPolylines& in) {
  const auto& z = in.apex_heights;
  if (z.size() < 5 || in.signs.empty()) return false;
  const std::size_t sides = z.size() - 2;
  const bool repeats = z[sides] == z[0] && z[sides + 1] == z[1];
  const bool uniform = std::all_of(in.signs.begin(), in.signs.end(), [&](Sign s) { return s == in.signs.front(); });
  return repeats && uniform;
}

}  // namespace phedra
