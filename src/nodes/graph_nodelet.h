#pragma once
// Each stage of the graph is one class built from (node handle, private node handle, config):
// GraphNodelet makes it a nodelet (nodelets.cpp), node_main.cpp.in a node of its own.

#include <nodelet/nodelet.h>

#include <exception>
#include <memory>

#include "adaptive_lego_loam/ros/node_config.h"

namespace adaptive_lego_loam::nodes {

template <class Node>
class GraphNodelet : public nodelet::Nodelet {
 private:
  // A bad config fails the load (nodelet load then exits non-zero, as the node would).
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& private_nh = getPrivateNodeHandle();
    try {
      node_ = std::make_unique<Node>(nh, private_nh, ros_bridge::load_node_config(private_nh));
    } catch (const std::exception& e) {
      NODELET_FATAL("%s: %s", getName().c_str(), e.what());
      throw;
    }
  }

  std::unique_ptr<Node> node_;
};

}  // namespace adaptive_lego_loam::nodes
