#pragma once
// Faults injected into the simulated IMU's and wheel odometry's samples, for testing what the
// pipeline does with a sensor that misbehaves. A spec is a comma-separated list of
// SENSOR:KIND@TIME, SENSOR imu or wheel, TIME in s on the scans' clock, KIND one of
//   nan        the first sample at or after TIME: every value NaN
//   repeat     that sample carries the stamp of the one before (a repeated stamp)
//   disorder   that sample and the next swap places (stamps out of order)
//   gap        no samples in [TIME, TIME + 2 s)
//   rate_drop  in [TIME, TIME + 2 s) only every 4th sample (a quarter of the rate)
//   absurd     that sample beyond any vehicle: the IMU 100 rad/s and 500 m/s^2 on every axis,
//              the wheel odometry 300 m/s forward
// e.g. "imu:nan@3,imu:gap@5,wheel:absurd@4".

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/motion_sensors/samples.h"

namespace adaptive_lego_loam::sim {

enum class FaultKind { kNan, kRepeat, kDisorder, kGap, kRateDrop, kAbsurd };

struct SensorFault {
  bool imu = true;  // else the wheel odometry
  FaultKind kind = FaultKind::kNan;
  double time = 0.0;
};

// Throws std::invalid_argument naming the item and what was expected.
std::vector<SensorFault> parse_faults(const std::string& spec);
std::string fault_name(const SensorFault& fault);  // "imu:nan@3"

// Applies the faults of that sensor, those that change single samples first, in the spec's order,
// then those that remove samples.
void apply_faults(const std::vector<SensorFault>& faults, std::vector<ImuSample>& samples);
void apply_faults(const std::vector<SensorFault>& faults,
                  std::vector<WheelOdometrySample>& samples);

}  // namespace adaptive_lego_loam::sim
