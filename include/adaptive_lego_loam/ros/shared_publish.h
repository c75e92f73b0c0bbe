#pragma once
// Publishing by shared pointer: in one nodelet manager a subscriber gets this very message
// instead of a serialised copy. The message must not change once published.

#include <ros/publisher.h>

#include <boost/make_shared.hpp>
#include <type_traits>
#include <utility>

namespace adaptive_lego_loam::ros_bridge {

template <class Message>
void publish_shared(const ros::Publisher& publisher, Message&& message) {
  publisher.publish(boost::make_shared<std::decay_t<Message>>(std::forward<Message>(message)));
}

}  // namespace adaptive_lego_loam::ros_bridge
