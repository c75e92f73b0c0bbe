#pragma once
// Seeded randomness with the distribution math written out, so that a seed gives the same
// numbers with any standard library (std::*_distribution is implementation-defined).

#include <cstdint>
#include <random>

namespace adaptive_lego_loam::sim {

// SplitMix64 finaliser: a well-mixed 64-bit value from any input.
inline uint64_t mix64(uint64_t value) {
  value += 0x9E3779B97F4A7C15ull;
  value = (value ^ (value >> 30)) * 0xBF58476D1CE4E5B9ull;
  value = (value ^ (value >> 27)) * 0x94D049BB133111EBull;
  return value ^ (value >> 31);
}

// A seed for one purpose (stream) derived from the run's seed, so that adding a draw in one
// part of the generator does not shift the numbers of another.
inline uint64_t derive_seed(uint64_t seed, uint64_t stream, uint64_t index = 0) {
  return mix64(mix64(mix64(seed) ^ stream) ^ index);
}

// Uniform in [0, 1) from a hashed value: stateless randomness per (object, frame).
inline double unit_from_bits(uint64_t bits) {
  return (bits >> 11) * 0x1.0p-53;
}

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}

  double uniform() { return unit_from_bits(engine_()); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // An integer in [lo, hi].
  int integer(int lo, int hi) {
    return lo + static_cast<int>(uniform() * (static_cast<double>(hi) - lo + 1.0));
  }
  bool chance(double probability) { return uniform() < probability; }
  double normal(double mean, double sigma) { return mean + sigma * standard_normal(); }
  double standard_normal();
  double sign() { return chance(0.5) ? 1.0 : -1.0; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace adaptive_lego_loam::sim
