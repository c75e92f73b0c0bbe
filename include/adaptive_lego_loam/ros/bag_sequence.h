#pragma once
// Scans from the PointCloud2 messages of a rosbag, for the offline tools.

#include <memory>
#include <string>

#include "adaptive_lego_loam/io/point_fields.h"
#include "adaptive_lego_loam/io/scan_sequence.h"

namespace adaptive_lego_loam::ros_bridge {

// `topic` empty: the bag's only PointCloud2 topic (an error naming the candidates when there are
// several). Throws IoError naming the bag when it cannot be opened or has no such topic.
// `options`: how the clouds are decoded (decode_points).
std::unique_ptr<ScanSequence> open_bag_sequence(const std::string& path, const std::string& topic,
                                                const DecodeOptions& options = {});

}  // namespace adaptive_lego_loam::ros_bridge
