#include "adaptive_lego_loam/ros/stamp_matcher.h"

#include <cstdio>
#include <stdexcept>

namespace adaptive_lego_loam::ros_bridge {

std::string StampMatcher::Dropped::describe() const {
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%.3f", stamp.toSec());
  std::string text = "scan at " + std::string(seconds) + " s dropped: ";
  if (late) return text + "it arrived after a later scan was complete";
  text += "no";
  for (std::size_t i = 0; i < missing.size(); ++i)
    text += (i == 0 ? " " : ", ") + missing[i];
  return text + " for it";
}

StampMatcher::StampMatcher(std::vector<std::string> slot_names, std::size_t max_pending)
    : slot_names_(std::move(slot_names)), max_pending_(max_pending) {
  if (slot_names_.empty()) throw std::invalid_argument("StampMatcher: no slot");
  if (max_pending_ == 0) throw std::invalid_argument("StampMatcher: max_pending must be >= 1");
}

StampMatcher::Dropped StampMatcher::partial(const ros::Time& stamp,
                                            const std::vector<Message>& messages, bool late) const {
  Dropped dropped;
  dropped.stamp = stamp;
  dropped.late = late;
  for (std::size_t slot = 0; slot < messages.size(); ++slot) {
    if (!messages[slot]) dropped.missing.push_back(slot_names_[slot]);
  }
  return dropped;
}

std::optional<StampMatcher::Group> StampMatcher::add(std::size_t slot, const ros::Time& stamp,
                                                     Message message) {
  if (slot >= slot_names_.size()) throw std::out_of_range("StampMatcher: no such slot");
  // Far older than the last group: time went back (a bag played again), not a late message.
  if (last_completed_ && stamp + ros::Duration(kJumpBack) < *last_completed_) {
    pending_.clear();
    last_completed_.reset();
    ++restarts_;
  }
  if (last_completed_ && stamp <= *last_completed_) {
    std::vector<Message> alone(slot_names_.size());
    alone[slot] = message;
    dropped_.push_back(partial(stamp, alone, true));
    return std::nullopt;
  }
  std::vector<Message>& messages = pending_[stamp];
  messages.resize(slot_names_.size());
  messages[slot] = std::move(message);

  for (const Message& m : messages) {
    if (!m) {
      while (pending_.size() > max_pending_) {
        const auto oldest = pending_.begin();
        dropped_.push_back(partial(oldest->first, oldest->second, false));
        pending_.erase(oldest);
      }
      return std::nullopt;
    }
  }
  Group group{stamp, std::move(messages)};
  // Every older group is incomplete and can no longer complete in order.
  auto it = pending_.begin();
  for (; it->first < stamp; ++it)
    dropped_.push_back(partial(it->first, it->second, false));
  pending_.erase(pending_.begin(), std::next(it));
  last_completed_ = stamp;
  return group;
}

std::vector<StampMatcher::Dropped> StampMatcher::take_dropped() {
  std::vector<Dropped> dropped;
  dropped.swap(dropped_);
  return dropped;
}

ScanPairing::ScanPairing(const std::string& node, std::vector<std::string> slot_names,
                         std::size_t max_pending, double warning_period_s)
    : matcher_(std::move(slot_names), max_pending), warning_(node, warning_period_s) {}

std::optional<StampMatcher::Group> ScanPairing::add(std::size_t slot, const ros::Time& stamp,
                                                    StampMatcher::Message message) {
  std::optional<StampMatcher::Group> group = matcher_.add(slot, stamp, std::move(message));
  for (const StampMatcher::Dropped& dropped : matcher_.take_dropped()) {
    warning_(dropped.describe());
    ++dropped_;
  }
  return group;
}

}  // namespace adaptive_lego_loam::ros_bridge
