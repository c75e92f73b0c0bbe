#include "adaptive_lego_loam/sim/speed_profile.h"

#include <cmath>
#include <stdexcept>

namespace adaptive_lego_loam::sim {
namespace {

// A change's shape: ramp up over T, hold the peak acceleration A for H, ramp down over T.
struct Shape {
  double sign, peak, ramp, hold;
};

Shape shape_of(const SpeedChange& change) {
  const double size = std::abs(change.delta_mps), ramp = change.ramp_s;
  const double sign = change.delta_mps < 0.0 ? -1.0 : 1.0;
  if (size >= change.acceleration_mps2 * ramp)
    return {sign, change.acceleration_mps2, ramp, size / change.acceleration_mps2 - ramp};
  return {sign, size / ramp, ramp, 0.0};
}

// Acceleration, speed and distance since the change began, tau s into it; the ramps are half
// cosines, a(tau) = A / 2 (1 - cos(pi tau / T)) up and A / 2 (1 + cos(pi u / T)) down.
struct State {
  double acceleration = 0.0, speed = 0.0, distance = 0.0;
};

State state_at(const Shape& s, double tau) {
  const double a = s.sign * s.peak, t = s.ramp, k = M_PI / t, c = t * t / (M_PI * M_PI);
  State out;
  if (tau <= 0.0) return out;
  if (tau <= t) {
    out.acceleration = 0.5 * a * (1.0 - std::cos(k * tau));
    out.speed = 0.5 * a * (tau - std::sin(k * tau) / k);
    out.distance = 0.5 * a * (0.5 * tau * tau - c * (1.0 - std::cos(k * tau)));
    return out;
  }
  const double v1 = 0.5 * a * t, x1 = 0.5 * a * (0.5 * t * t - 2.0 * c);
  if (tau <= t + s.hold) {
    const double u = tau - t;
    out.acceleration = a;
    out.speed = v1 + a * u;
    out.distance = x1 + v1 * u + 0.5 * a * u * u;
    return out;
  }
  const double v2 = v1 + a * s.hold, x2 = x1 + v1 * s.hold + 0.5 * a * s.hold * s.hold;
  const double u = std::min(tau - t - s.hold, t);
  out.acceleration = 0.5 * a * (1.0 + std::cos(k * u));
  out.speed = v2 + 0.5 * a * (u + std::sin(k * u) / k);
  out.distance = x2 + v2 * u + 0.5 * a * (0.5 * u * u + c * (1.0 - std::cos(k * u)));
  const double after = tau - 2.0 * t - s.hold;
  if (after > 0.0) {  // done: the new speed from here on
    out.acceleration = 0.0;
    out.distance += out.speed * after;
  }
  return out;
}

State change_state(const SpeedChange& change, double time) {
  if (!(change.acceleration_mps2 > 0.0 && change.ramp_s > 0.0 && change.start_time_s >= 0.0)) {
    throw std::invalid_argument(
        "speed change: acceleration and ramp must be positive, the start time not negative");
  }
  return state_at(shape_of(change), time - change.start_time_s);
}

}  // namespace

double SpeedChange::duration() const {
  const Shape shape = shape_of(*this);
  return 2.0 * shape.ramp + shape.hold;
}

double SpeedChange::speed(double time) const {
  return change_state(*this, time).speed;
}

double SpeedChange::acceleration(double time) const {
  return change_state(*this, time).acceleration;
}

double SpeedChange::distance(double time) const {
  return change_state(*this, time).distance;
}

double SpeedProfile::speed(double time) const {
  double v = cruise_mps * (1.0 + variation * std::sin(2.0 * M_PI / period_s * time + phase));
  for (const SpeedChange& change : changes)
    v += change.speed(time);
  return v;
}

double SpeedProfile::acceleration(double time) const {
  const double omega = 2.0 * M_PI / period_s;
  double a = cruise_mps * variation * omega * std::cos(omega * time + phase);
  for (const SpeedChange& change : changes)
    a += change.acceleration(time);
  return a;
}

double SpeedProfile::distance(double time) const {
  const double omega = 2.0 * M_PI / period_s;
  double d =
      cruise_mps * (time - variation / omega * (std::cos(omega * time + phase) - std::cos(phase)));
  for (const SpeedChange& change : changes)
    d += change.distance(time);
  return d;
}

double SpeedProfile::time_at_distance(double target, double from) const {
  double low = from, high = from + 1.0;
  for (int doubling = 0; distance(high) < target; ++doubling, high = from + 2.0 * (high - from)) {
    if (doubling > 40) throw std::invalid_argument("speed profile never covers the distance");
  }
  if (distance(low) >= target) return low;
  for (int i = 0; i < 100 && high - low > 1e-9; ++i) {
    const double middle = 0.5 * (low + high);
    (distance(middle) < target ? low : high) = middle;
  }
  return high;
}

}  // namespace adaptive_lego_loam::sim
