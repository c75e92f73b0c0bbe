#include "adaptive_lego_loam/sim/random.h"

#include <cmath>

namespace adaptive_lego_loam::sim {

double Rng::normal(double mean, double sigma) {
  // Box-Muller; the second value of each pair is kept for the next call.
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return mean + sigma * spare_normal_;
  }
  const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
  const double u2 = uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  spare_normal_ = radius * std::sin(2.0 * M_PI * u2);
  has_spare_normal_ = true;
  return mean + sigma * radius * std::cos(2.0 * M_PI * u2);
}

}  // namespace adaptive_lego_loam::sim
