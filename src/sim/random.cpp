#include "adaptive_lego_loam/sim/random.h"

#include <cmath>

namespace adaptive_lego_loam::sim {
namespace {

// Marsaglia and Tsang's ziggurat for the standard normal ("The Ziggurat Method for Generating
// Random Variables", 2000), 128 layers. Most draws cost one table look-up and a multiplication;
// exp and log are needed only at the layers' edges and in the tail (about 2 % of draws).
struct Ziggurat {
  static constexpr int kLayers = 128;
  static constexpr double kTail = 3.442619855899;       // r: where the tail starts
  static constexpr double kArea = 9.91256303526217e-3;  // v: area of each layer
  static constexpr double kScale = 2147483648.0;        // 2^31: magnitudes are 31-bit integers

  uint32_t k[kLayers];  // below k[i] a draw of layer i is inside the layer's inner box
  double w[kLayers];    // x = magnitude * w[i]
  double f[kLayers];    // exp(-x_i^2 / 2) at the layer's outer edge

  Ziggurat() {
    double x = kTail, previous = kTail;
    const double q = kArea / std::exp(-0.5 * x * x);
    k[0] = static_cast<uint32_t>(x / q * kScale);
    k[1] = 0;
    w[0] = q / kScale;
    w[kLayers - 1] = x / kScale;
    f[0] = 1.0;
    f[kLayers - 1] = std::exp(-0.5 * x * x);
    for (int i = kLayers - 2; i >= 1; --i) {
      x = std::sqrt(-2.0 * std::log(kArea / x + std::exp(-0.5 * x * x)));
      k[i + 1] = static_cast<uint32_t>(x / previous * kScale);
      previous = x;
      f[i] = std::exp(-0.5 * x * x);
      w[i] = x / kScale;
    }
  }
};

const Ziggurat& ziggurat() {
  static const Ziggurat table;
  return table;
}

}  // namespace

double Rng::standard_normal() {
  const Ziggurat& z = ziggurat();
  while (true) {
    // Layer from the low 7 bits, sign and 31-bit magnitude from the high 32: independent bits.
    const uint64_t bits = engine_();
    const int layer = static_cast<int>(bits & (Ziggurat::kLayers - 1));
    const uint32_t magnitude = static_cast<uint32_t>(bits >> 33);
    const double sign = (bits >> 32) & 1u ? -1.0 : 1.0;
    const double x = magnitude * z.w[layer];
    if (magnitude < z.k[layer]) return sign * x;  // inside the layer's box: ~98 %
    if (layer == 0) {
      // The tail beyond r (Marsaglia's method).
      double tail, y;
      do {
        tail = -std::log(1.0 - uniform()) / Ziggurat::kTail;
        y = -std::log(1.0 - uniform());
      } while (y + y < tail * tail);
      return sign * (Ziggurat::kTail + tail);
    }
    // The wedge between the box and the curve.
    if (z.f[layer] + uniform() * (z.f[layer - 1] - z.f[layer]) < std::exp(-0.5 * x * x))
      return sign * x;
  }
}

}  // namespace adaptive_lego_loam::sim
