#pragma once
// Groups the messages of several topics that belong to one scan (equal header stamps), as the
// nodes downstream of image_projection need them: a group is handed on once every topic has
// delivered its message for that stamp. Partial groups are dropped, and reported, when a later
// scan completes first or when too many are pending; a message older than the last completed
// group is dropped at once, unless it is more than a second older: then time went back (a bag
// played again in a loop) and the matcher starts over.

#include <ros/time.h>

#include <boost/shared_ptr.hpp>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_lego_loam/ros/node_logging.h"

namespace adaptive_lego_loam::ros_bridge {

class StampMatcher {
 public:
  using Message = boost::shared_ptr<const void>;

  struct Group {
    ros::Time stamp;
    std::vector<Message> messages;  // one per slot, in slot order
    template <class T>
    boost::shared_ptr<const T> get(std::size_t slot) const {
      return boost::static_pointer_cast<const T>(messages.at(slot));
    }
  };

  struct Dropped {
    ros::Time stamp;
    std::vector<std::string> missing;  // slots that had not delivered
    bool late = false;                 // arrived after a later group completed
    std::string describe() const;
  };

  static constexpr double kJumpBack = 1.0;  // s

  // `slot_names` (e.g. the topics) name the slots in reports; `max_pending` >= 1.
  StampMatcher(std::vector<std::string> slot_names, std::size_t max_pending);

  // Adds the message of `slot` for `stamp` (replacing an earlier one of that slot and stamp).
  // Returns the group when this completes it.
  std::optional<Group> add(std::size_t slot, const ros::Time& stamp, Message message);

  // Partial groups dropped since the last call, oldest first.
  std::vector<Dropped> take_dropped();

  std::size_t pending() const { return pending_.size(); }
  std::size_t slots() const { return slot_names_.size(); }
  // Times it started over after time went back.
  int restarts() const { return restarts_; }

 private:
  Dropped partial(const ros::Time& stamp, const std::vector<Message>& messages, bool late) const;

  std::vector<std::string> slot_names_;
  std::size_t max_pending_;
  std::map<ros::Time, std::vector<Message>> pending_;
  std::optional<ros::Time> last_completed_;
  std::vector<Dropped> dropped_;
  int restarts_ = 0;
};

// The messages of one scan from several topics, for a node downstream of image_projection: grouped
// by stamp, and the incomplete groups logged as the node's warnings (throttled).
class ScanPairing {
 public:
  ScanPairing(const std::string& node, std::vector<std::string> slot_names, std::size_t max_pending,
              double warning_period_s);
  // StampMatcher::add, logging the groups it dropped.
  std::optional<StampMatcher::Group> add(std::size_t slot, const ros::Time& stamp,
                                         StampMatcher::Message message);
  // Incomplete groups dropped so far.
  long dropped() const { return dropped_; }

 private:
  StampMatcher matcher_;
  ThrottledWarning warning_;
  long dropped_ = 0;
};

}  // namespace adaptive_lego_loam::ros_bridge
