#include "adaptive_lego_loam/core/loop_closure/place_recognition.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {
namespace {

double yaw_of(const Eigen::Matrix3d& rotation) {
  return std::atan2(rotation(1, 0), rotation(0, 0));
}

double squared_distance(const float* a, const std::vector<float>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum;
}

}  // namespace

Eigen::Matrix3f levelling(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d rotation = pose.rotation();
  const Eigen::Matrix3d yaw(Eigen::AngleAxisd(yaw_of(rotation), Eigen::Vector3d::UnitZ()));
  return (yaw.transpose() * rotation).cast<float>();
}

PlaceRecognition::PlaceRecognition(const LoopClosureParams& params) : params_(params) {}

PlaceDescriptor PlaceRecognition::describe(const std::vector<const Cloud*>& clouds,
                                           const Eigen::Isometry3d& pose) const {
  PlaceDescriptor descriptor(params_.place);
  const Eigen::Matrix3f level = levelling(pose);
  for (const Cloud* cloud : clouds)
    descriptor.add(*cloud, level);
  descriptor.finish();
  return descriptor;
}

void PlaceRecognition::add(int keyframe, double stamp, PlaceDescriptor descriptor) {
  const auto rings = static_cast<std::size_t>(params_.place.rings);
  if (descriptor.empty() || descriptor.ring_key().size() != rings) return;
  ring_keys_.insert(ring_keys_.end(), descriptor.ring_key().begin(), descriptor.ring_key().end());
  keyframes_.push_back(keyframe);
  stamps_.push_back(stamp);
  places_.push_back(std::move(descriptor));
}

void PlaceRecognition::forget(int first, int last) {
  const std::size_t rings = static_cast<std::size_t>(params_.place.rings);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < places_.size(); ++i) {
    if (keyframes_[i] >= first && keyframes_[i] <= last) continue;
    if (kept != i) {
      places_[kept] = std::move(places_[i]);
      keyframes_[kept] = keyframes_[i];
      stamps_[kept] = stamps_[i];
      std::copy_n(&ring_keys_[i * rings], rings, &ring_keys_[kept * rings]);
    }
    ++kept;
  }
  places_.resize(kept);
  keyframes_.resize(kept);
  stamps_.resize(kept);
  ring_keys_.resize(kept * rings);
}

std::optional<LoopCandidate> PlaceRecognition::candidate(const std::vector<Keyframe>& keyframes,
                                                         int current) const {
  if (!params_.place.enabled || places_.empty() || keyframes_.back() != current) {
    return std::nullopt;
  }
  const PlaceDescriptor& place = places_.back();
  const double newest_stamp = keyframes.at(current).stamp - params_.min_time_gap;
  const std::size_t rings = static_cast<std::size_t>(params_.place.rings);
  // The nearest ring keys first: a cheap, rotation-invariant look at every older place.
  std::vector<std::pair<double, std::size_t>> nearest;
  for (std::size_t i = 0; i < places_.size(); ++i) {
    if (stamps_[i] > newest_stamp || keyframes_[i] == current) continue;
    nearest.emplace_back(squared_distance(&ring_keys_[i * rings], place.ring_key()), i);
  }
  const std::size_t compared =
      std::min(nearest.size(), static_cast<std::size_t>(params_.place.candidates));
  std::partial_sort(nearest.begin(), nearest.begin() + compared, nearest.end(),
                    [](const auto& a, const auto& b) {
                      return a.first < b.first || (a.first == b.first && a.second < b.second);
                    });
  // Every compared place's distance, then the best, and the best elsewhere for distinctness.
  std::vector<std::pair<double, std::pair<int, int>>> compared_places;  // keyframe, shift
  for (std::size_t i = 0; i < compared; ++i) {
    int shift = 0;
    const std::size_t older = nearest[i].second;
    const double distance = place.distance(places_[older], &shift);
    compared_places.push_back({distance, {keyframes_[older], shift}});
  }
  const auto best =
      std::min_element(compared_places.begin(), compared_places.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
  if (best == compared_places.end() || best->first > params_.place.max_distance) {
    return std::nullopt;
  }
  const Keyframe& matched = keyframes.at(best->second.first);
  for (const auto& [distance, other] : compared_places) {
    const double apart =
        (keyframes.at(other.first).pose.translation() - matched.pose.translation()).norm();
    if (apart > params_.place.elsewhere_distance &&
        best->first > params_.place.max_ratio * distance) {
      return std::nullopt;  // as good a match elsewhere: no telling which place this is
    }
  }
  const Keyframe& now = keyframes.at(current);
  LoopCandidate candidate;
  candidate.matched_index = best->second.first;
  candidate.source = CandidateSource::kPlace;
  candidate.place_distance = best->first;
  // At the matched keyframe, turned by the relative yaw, with the current roll and pitch.
  const double heading = yaw_of(matched.pose.rotation()) + place.yaw_of_shift(best->second.second);
  candidate.guess.linear() =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      levelling(now.pose).cast<double>();
  candidate.guess.translation() = matched.pose.translation();
  return candidate;
}

std::size_t PlaceRecognition::bytes() const {
  std::size_t total = places_.capacity() * sizeof(PlaceDescriptor) +
                      keyframes_.capacity() * sizeof(int) + stamps_.capacity() * sizeof(double) +
                      ring_keys_.capacity() * sizeof(float);
  for (const PlaceDescriptor& place : places_)
    total += place.bytes();
  return total;
}

}  // namespace adaptive_lego_loam
