#include "adaptive_lego_loam/ros/bag_sequence.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/PointCloud2.h>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/ros/cloud_conversions.h"

namespace adaptive_lego_loam::ros_bridge {
namespace {

class BagSequence : public ScanSequence {
 public:
  BagSequence(const std::string& path, const std::string& topic, const DecodeOptions& options)
      : path_(path), topic_(topic), options_(options) {
    try {
      bag_.open(path, rosbag::bagmode::Read);
    } catch (const rosbag::BagException& e) {
      throw IoError(path + ": cannot open bag: " + e.what());
    }
    if (topic_.empty()) topic_ = only_cloud_topic();
    view_ = std::make_unique<rosbag::View>(bag_, rosbag::TopicQuery(topic_));
    if (view_->size() == 0) throw IoError(path + ": no message on topic " + topic_);
    position_ = view_->begin();
  }

  std::optional<Scan> next() override {
    if (position_ == view_->end()) return std::nullopt;
    // The iterator owns the instance it points at: read it before moving on.
    const rosbag::MessageInstance& message = *position_;
    const auto cloud = message.instantiate<sensor_msgs::PointCloud2>();
    const std::string data_type = message.getDataType();
    // The cloud's own stamp when it has one, else when the bag recorded it.
    last_stamp_ = cloud && !cloud->header.stamp.isZero() ? cloud->header.stamp.toSec()
                                                         : message.getTime().toSec();
    // Moved on first: a scan that cannot be read is skipped when the caller goes on.
    ++position_;
    if (!cloud) {
      throw IoError(path_ + ": topic " + topic_ + " holds " + data_type +
                    ", expected sensor_msgs/PointCloud2");
    }
    return from_ros(*cloud, path_ + ":" + topic_, options_);
  }
  int size() const override { return static_cast<int>(view_->size()); }
  std::string describe() const override {
    return "bag " + path_ + " topic " + topic_ + " (" + std::to_string(size()) + " scans)";
  }

 private:
  std::string only_cloud_topic() {
    rosbag::View all(bag_);
    std::vector<std::string> topics;
    for (const rosbag::ConnectionInfo* info : all.getConnections()) {
      if (info->datatype == "sensor_msgs/PointCloud2" &&
          std::find(topics.begin(), topics.end(), info->topic) == topics.end()) {
        topics.push_back(info->topic);
      }
    }
    if (topics.size() == 1) return topics.front();
    if (topics.empty()) throw IoError(path_ + ": no sensor_msgs/PointCloud2 topic");
    std::string names;
    for (const auto& t : topics)
      names += " " + t;
    throw IoError(path_ + ": several PointCloud2 topics, choose one with --topic:" + names);
  }

  std::string path_, topic_;
  DecodeOptions options_;
  rosbag::Bag bag_;
  std::unique_ptr<rosbag::View> view_;
  rosbag::View::iterator position_;
};

}  // namespace

std::unique_ptr<ScanSequence> open_bag_sequence(const std::string& path, const std::string& topic,
                                                const DecodeOptions& options) {
  return std::make_unique<BagSequence>(path, topic, options);
}

}  // namespace adaptive_lego_loam::ros_bridge
