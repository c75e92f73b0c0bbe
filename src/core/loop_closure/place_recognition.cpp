#include "adaptive_lego_loam/core/loop_closure/place_recognition.h"

#include <algorithm>
#include <cmath>

namespace adaptive_lego_loam {
namespace {

double yaw_of(const Eigen::Matrix3d& rotation) {
  return std::atan2(rotation(1, 0), rotation(0, 0));
}

double squared_distance(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
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
  if (descriptor.empty()) return;
  places_.push_back({keyframe, stamp, std::move(descriptor)});
}

void PlaceRecognition::forget(int first, int last) {
  places_.erase(std::remove_if(places_.begin(), places_.end(),
                               [&](const Place& place) {
                                 return place.keyframe >= first && place.keyframe <= last;
                               }),
                places_.end());
}

std::optional<LoopCandidate> PlaceRecognition::candidate(const std::vector<Keyframe>& keyframes,
                                                         int current) const {
  if (!params_.place.enabled || places_.empty() || places_.back().keyframe != current) {
    return std::nullopt;
  }
  const PlaceDescriptor& place = places_.back().descriptor;
  const double newest_stamp = keyframes.at(current).stamp - params_.min_time_gap;
  // The nearest ring keys first: a cheap, rotation-invariant look at every older place.
  std::vector<std::pair<double, const Place*>> nearest;
  for (const Place& older : places_) {
    if (older.stamp > newest_stamp || older.keyframe == current) continue;
    nearest.emplace_back(squared_distance(older.descriptor.ring_key(), place.ring_key()), &older);
  }
  const std::size_t compared =
      std::min(nearest.size(), static_cast<std::size_t>(params_.place.candidates));
  std::partial_sort(nearest.begin(), nearest.begin() + compared, nearest.end(),
                    [](const auto& a, const auto& b) {
                      return a.first < b.first || (a.first == b.first && a.second < b.second);
                    });
  // Every compared place's distance, then the best, and the best elsewhere for distinctness.
  std::vector<std::pair<double, std::pair<const Place*, int>>> compared_places;
  for (std::size_t i = 0; i < compared; ++i) {
    int shift = 0;
    const double distance = place.distance(nearest[i].second->descriptor, &shift);
    compared_places.push_back({distance, {nearest[i].second, shift}});
  }
  const auto best =
      std::min_element(compared_places.begin(), compared_places.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
  if (best == compared_places.end() || best->first > params_.place.max_distance) {
    return std::nullopt;
  }
  const Keyframe& matched = keyframes.at(best->second.first->keyframe);
  for (const auto& [distance, other] : compared_places) {
    const double apart =
        (keyframes.at(other.first->keyframe).pose.translation() - matched.pose.translation())
            .norm();
    if (apart > params_.place.elsewhere_distance &&
        best->first > params_.place.max_ratio * distance) {
      return std::nullopt;  // as good a match elsewhere: no telling which place this is
    }
  }
  const Keyframe& now = keyframes.at(current);
  LoopCandidate candidate;
  candidate.matched_index = best->second.first->keyframe;
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
  std::size_t total = places_.capacity() * sizeof(Place);
  for (const Place& place : places_)
    total += place.descriptor.bytes();
  return total;
}

}  // namespace adaptive_lego_loam
