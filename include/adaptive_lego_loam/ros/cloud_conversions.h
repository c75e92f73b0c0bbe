#pragma once
// Conversions between sensor_msgs/PointCloud2 and the core's Scan: the only place that knows both.

#include <sensor_msgs/PointCloud2.h>

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/scan.h"
#include "adaptive_lego_loam/io/point_fields.h"

namespace adaptive_lego_loam::ros_bridge {

// Any PointCloud2 with x, y, z (float32/float64), with or without intensity, ring and time
// fields (see decode_points for the accepted names). Throws IoError naming `source` (the topic)
// when a required field is missing or the message is malformed.
Scan from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source,
              const DecodeOptions& options = {});
// The same into `scan`, reusing its point buffer from one message to the next.
void from_ros(const sensor_msgs::PointCloud2& msg, const std::string& source, Scan& scan,
              const DecodeOptions& options = {});

// x, y, z, intensity, and ring (uint16) and time (float32, s) when `with_ring_and_time`.
sensor_msgs::PointCloud2 to_ros(const std::vector<ScanPoint>& points,
                                const std_msgs::Header& header, bool with_ring_and_time = false);
// The same with ring and time, each point's ring taken from `rings` (one entry a point).
sensor_msgs::PointCloud2 to_ros(const std::vector<ScanPoint>& points,
                                const std::vector<uint16_t>& rings, const std_msgs::Header& header);

}  // namespace adaptive_lego_loam::ros_bridge
