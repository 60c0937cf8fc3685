#pragma once
// The minimum-jerk profile of a point-to-point hand movement (Flash & Hogan 1985), shared by the children's fingers
// and the logic-only simulator's tray.

#include <algorithm>

namespace freeplay::agents {

/// Share of the way covered at normalised time `tau` (clamped to [0, 1]) by a minimum-jerk movement.
inline double min_jerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  const double t3 = tau * tau * tau;
  return t3 * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

}  // namespace freeplay::agents
