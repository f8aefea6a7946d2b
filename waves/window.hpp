// A closed time window [t0, t1] (the whole series by default): where a wave analysis or a
// comparison metric looks.
#pragma once

#include <limits>

namespace swell {

struct Window {
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  bool contains(double t) const { return t >= t0 && t <= t1; }
};

}  // namespace swell
