#include "adaptive_lego_loam/sim/motion_sensor_faults.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace adaptive_lego_loam::sim {
namespace {

constexpr double kRemovalSpan = 2.0;  // s, of a gap or a rate drop
constexpr int kRateDropKeepEvery = 4;

const std::pair<const char*, FaultKind> kKinds[] = {{"nan", FaultKind::kNan},
                                                    {"repeat", FaultKind::kRepeat},
                                                    {"disorder", FaultKind::kDisorder},
                                                    {"gap", FaultKind::kGap},
                                                    {"rate_drop", FaultKind::kRateDrop},
                                                    {"absurd", FaultKind::kAbsurd}};

std::string kind_list() {
  std::string list;
  for (const auto& [name, kind] : kKinds)
    list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

SensorFault parse_fault(const std::string& item) {
  const std::string expected = "'" + item +
                               "': expected SENSOR:KIND@TIME (SENSOR imu or wheel; KIND " +
                               kind_list() + "; TIME in s)";
  const std::size_t colon = item.find(':'), at = item.find('@');
  if (colon == std::string::npos || at == std::string::npos || at < colon)
    throw std::invalid_argument(expected);
  SensorFault fault;
  const std::string sensor = item.substr(0, colon);
  if (sensor != "imu" && sensor != "wheel") throw std::invalid_argument(expected);
  fault.imu = sensor == "imu";
  const std::string kind = item.substr(colon + 1, at - colon - 1);
  const auto known = std::find_if(std::begin(kKinds), std::end(kKinds),
                                  [&](const auto& entry) { return kind == entry.first; });
  if (known == std::end(kKinds)) throw std::invalid_argument(expected);
  fault.kind = known->second;
  const std::string time = item.substr(at + 1);
  std::size_t used = 0;
  try {
    fault.time = std::stod(time, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (time.empty() || used != time.size() || !std::isfinite(fault.time))
    throw std::invalid_argument(expected);
  return fault;
}

void make_nan(ImuSample& s) {
  s.angular_velocity.setConstant(std::numeric_limits<double>::quiet_NaN());
  s.linear_acceleration.setConstant(std::numeric_limits<double>::quiet_NaN());
}

void make_nan(WheelOdometrySample& s) {
  s.linear_velocity.setConstant(std::numeric_limits<double>::quiet_NaN());
  s.angular_velocity.setConstant(std::numeric_limits<double>::quiet_NaN());
}

void make_absurd(ImuSample& s) {
  s.angular_velocity.setConstant(100.0);
  s.linear_acceleration.setConstant(500.0);
}

void make_absurd(WheelOdometrySample& s) {
  s.linear_velocity.x() = 300.0;
}

bool removes(FaultKind kind) {
  return kind == FaultKind::kGap || kind == FaultKind::kRateDrop;
}

template <typename Sample>
void apply(const std::vector<SensorFault>& faults, bool imu, std::vector<Sample>& samples) {
  for (const SensorFault& fault : faults) {
    if (fault.imu != imu || removes(fault.kind)) continue;
    const auto found = std::find_if(samples.begin(), samples.end(),
                                    [&](const Sample& s) { return s.stamp >= fault.time; });
    if (found == samples.end()) continue;
    const std::size_t i = static_cast<std::size_t>(found - samples.begin());
    switch (fault.kind) {
      case FaultKind::kNan:
        make_nan(samples[i]);
        break;
      case FaultKind::kAbsurd:
        make_absurd(samples[i]);
        break;
      case FaultKind::kRepeat:
        if (i > 0) samples[i].stamp = samples[i - 1].stamp;
        break;
      case FaultKind::kDisorder:
        if (i + 1 < samples.size()) std::swap(samples[i], samples[i + 1]);
        break;
      default:
        break;
    }
  }
  for (const SensorFault& fault : faults) {
    if (fault.imu != imu || !removes(fault.kind)) continue;
    std::vector<Sample> kept;
    int inside = 0;
    for (const Sample& s : samples) {
      const bool within = s.stamp >= fault.time && s.stamp < fault.time + kRemovalSpan;
      if (!within || (fault.kind == FaultKind::kRateDrop && inside++ % kRateDropKeepEvery == 0))
        kept.push_back(s);
    }
    samples = std::move(kept);
  }
}

}  // namespace

std::vector<SensorFault> parse_faults(const std::string& spec) {
  std::vector<SensorFault> faults;
  std::istringstream items(spec);
  std::string item;
  while (std::getline(items, item, ','))
    faults.push_back(parse_fault(item));
  if (faults.empty()) throw std::invalid_argument("'" + spec + "': no faults listed");
  return faults;
}

std::string fault_name(const SensorFault& fault) {
  std::string kind;
  for (const auto& [name, k] : kKinds)
    if (k == fault.kind) kind = name;
  std::ostringstream out;
  out << (fault.imu ? "imu" : "wheel") << ':' << kind << '@' << fault.time;
  return out.str();
}

void apply_faults(const std::vector<SensorFault>& faults, std::vector<ImuSample>& samples) {
  apply(faults, true, samples);
}

void apply_faults(const std::vector<SensorFault>& faults,
                  std::vector<WheelOdometrySample>& samples) {
  apply(faults, false, samples);
}

}  // namespace adaptive_lego_loam::sim
