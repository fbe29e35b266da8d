#include "phedra/closed_profile.h"

#include <algorithm>

namespace phedra {

bool has_closed_profile(const std::vector<double>& z, const std::vector<Sign>& signs) {
  if (z.size() < 5 || signs.empty()) return false;
  const std::size_t sides = z.size() - 2;
  const bool repeats = z[sides] == z[0] && z[sides + 1] == z[1];
  const bool uniform = std::all_of(signs.begin(), signs.end(), [&](Sign s) { return s == signs.front(); });
  return repeats && uniform;
}

bool has_closed_profile(const ControlPolylines& in) { return has_closed_profile(in.apex_heights, in.signs); }

}  // namespace phedra
