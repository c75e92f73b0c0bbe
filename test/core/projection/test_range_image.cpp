#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "adaptive_lego_loam/core/clustering/segmenter.h"
#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/projection/range_image.h"
#include "adaptive_lego_loam/io/scan_files.h"

using namespace adaptive_lego_loam;

namespace {

const std::string kData = TEST_DATA_DIR;
const std::string kConfig = CONFIG_DIR;

double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(fraction * (values.size() - 1))];
}

// For each row: the elevation of its points seen from their beam's origin (the sensor origin
// raised by the beam's offset), minus the row's beam angle.
std::vector<std::vector<double>> elevation_residuals_deg(const RangeImage& image,
                                                         const SensorParams& sensor) {
  std::vector<std::vector<double>> residuals(image.rows());
  for (int cell = 0; cell < image.size(); ++cell) {
    if (!image.occupied(cell)) continue;
    const int row = image.row_of(cell);
    const ScanPoint& p = image.point(cell);
    const double offset = sensor.beam_offsets_m.empty() ? 0.0 : sensor.beam_offsets_m[row];
    const double elevation = std::atan2(p.z - offset, std::hypot(p.x, p.y)) * 180.0 / M_PI;
    residuals[row].push_back(elevation - sensor.beam_angles_deg[row]);
  }
  return residuals;
}

// Angle to the nearest neighbouring beam.
double row_spacing_deg(const SensorParams& sensor, int row) {
  const auto& angles = sensor.beam_angles_deg;
  double spacing = 180.0;
  if (row > 0) spacing = std::min(spacing, angles[row] - angles[row - 1]);
  if (row + 1 < sensor.rows) spacing = std::min(spacing, angles[row + 1] - angles[row]);
  return spacing;
}

}  // namespace

TEST(Projection, RealKittiFrameRowsFromElevation) {
  const Config config = load_config(kConfig + "/kitti.yaml");
  const Scan scan = read_kitti_bin(kData + "/kitti_seq07/velodyne/0000000000.bin");
  ASSERT_FALSE(scan.has_ring);
  RangeProjector projector(config.sensor);
  RangeImage image;
  projector.project(scan, image);
  const ProjectionStats& stats = image.stats();

  const auto residuals = elevation_residuals_deg(image, config.sensor);
  for (int row = 0; row < image.rows(); ++row) {
    SCOPED_TRACE("row " + std::to_string(row));
    ASSERT_GT(residuals[row].size(), 500u) << "row nearly empty";
    std::vector<double> magnitude;
    for (double r : residuals[row])
      magnitude.push_back(std::fabs(r));
    // 95 % of a row's points lie within a fifth of the spacing to the next beam: rows are beams,
    // not slices of elevation (binning alone would spread them over the whole spacing).
    EXPECT_LT(percentile(magnitude, 0.95), 0.2 * row_spacing_deg(config.sensor, row));
  }
  EXPECT_LT(double(stats.collisions) / stats.valid(), 0.02);
  EXPECT_GT(stats.projected, 0.95 * scan.points.size());
}

TEST(Projection, NominalBeamAnglesWouldMisplaceKittiPoints) {
  // The measured table matters: with KITTI's nominal angles and no offsets, points spread over
  // a large part of the row spacing. This guards the claim made in config/kitti.yaml.
  Config config = load_config(kConfig + "/kitti.yaml");
  config.sensor.beam_offsets_m.clear();
  for (int row = 0; row < 32; ++row)
    config.sensor.beam_angles_deg[row] = -24.33 + 0.5 * row;
  for (int row = 32; row < 64; ++row) {
    config.sensor.beam_angles_deg[row] = -8.33 + (row - 32) / 3.0;
  }
  const Scan scan = read_kitti_bin(kData + "/kitti_seq07/velodyne/0000000000.bin");
  RangeImage image;
  RangeProjector(config.sensor).project(scan, image);
  const auto residuals = elevation_residuals_deg(image, config.sensor);
  std::vector<double> magnitude;
  for (const auto& row : residuals) {
    for (double r : row)
      magnitude.push_back(std::fabs(r));
  }
  EXPECT_GT(percentile(magnitude, 0.5), 0.05);
}

TEST(Projection, RealVlp16FrameRowsFromChannel) {
  const Config config = load_config(kConfig + "/vlp16.yaml");
  const Scan scan = read_pcd(kData + "/vlp16/vlp16_indoor.pcd");
  ASSERT_TRUE(scan.has_ring);
  std::vector<int> input_per_ring(16, 0);
  for (const ScanPoint& p : scan.points)
    ++input_per_ring.at(p.ring);

  RangeImage image;
  RangeProjector(config.sensor).project(scan, image);
  const auto residuals = elevation_residuals_deg(image, config.sensor);
  for (int row = 0; row < 16; ++row) {
    SCOPED_TRACE("row " + std::to_string(row));
    if (input_per_ring[row] == 0) {
      // This indoor frame has no return at all on channel 0 (-15 deg): nothing to occupy.
      EXPECT_TRUE(residuals[row].empty());
      continue;
    }
    ASSERT_FALSE(residuals[row].empty());
    std::vector<double> magnitude;
    for (double r : residuals[row])
      magnitude.push_back(std::fabs(r));
    EXPECT_LT(percentile(magnitude, 0.95), 0.1 * 2.0);
  }
  EXPECT_EQ(std::count(input_per_ring.begin() + 1, input_per_ring.end(), 0), 0)
      << "channels 1-15 all have returns in the source frame";
  EXPECT_LT(double(image.stats().collisions) / image.stats().valid(), 0.02);
}

TEST(Projection, RingsMappedToMinusOneAreLeftOut) {
  // KITTI's scan with rings from the 64-beam table (as kitti_to_bag writes it), read with the
  // 16-ring config: rings 0, 4, ..., 60 become rows 0-15 and every other ring is left out.
  const Config kitti = load_config(kConfig + "/kitti.yaml");
  const Config thinned = load_config(kConfig + "/kitti_16rings.yaml");
  Scan scan = read_kitti_bin(kData + "/kitti_seq07/velodyne/0000000000.bin");
  RangeImage full;
  RangeProjector(kitti.sensor).project(scan, full);
  Scan with_rings;
  with_rings.has_ring = true;
  std::vector<int> full_per_ring(64, 0);
  for (int cell = 0; cell < full.size(); ++cell) {
    if (!full.occupied(cell)) continue;
    ScanPoint p = full.point(cell);
    p.ring = full.row_of(cell);
    ++full_per_ring[p.ring];
    with_rings.points.push_back(p);
  }

  RangeImage image;
  RangeProjector(thinned.sensor).project(with_rings, image);
  ASSERT_EQ(image.rows(), 16);
  std::vector<int> kept_per_row(16, 0);
  for (int cell = 0; cell < image.size(); ++cell) {
    if (image.occupied(cell)) ++kept_per_row[image.row_of(cell)];
  }
  int left_out = 0;
  for (int ring = 0; ring < 64; ++ring) {
    if (ring % 4 != 0) left_out += full_per_ring[ring];
  }
  for (int row = 0; row < 16; ++row) {
    SCOPED_TRACE("row " + std::to_string(row));
    EXPECT_GT(kept_per_row[row], 0.98 * full_per_ring[4 * row]);
    EXPECT_LE(kept_per_row[row], full_per_ring[4 * row]);
  }
  EXPECT_EQ(image.stats().outside_rows, left_out);
}

TEST(Projection, RowFromElevationPicksNearestBeam) {
  SensorParams sensor;
  sensor.rows = 3;
  sensor.columns = 360;
  sensor.ground_rows = 0;
  sensor.beam_angles_deg = {-10.0, 0.0, 10.0};
  RangeProjector projector(sensor);
  auto at = [&](double elevation_deg) {
    const double e = elevation_deg * M_PI / 180.0;
    return projector.row_from_elevation(10 * std::cos(e), 0.f, 10 * std::sin(e));
  };
  EXPECT_EQ(at(-10.0), 0);
  EXPECT_EQ(at(-5.5), 0);
  EXPECT_EQ(at(-4.5), 1);
  EXPECT_EQ(at(9.0), 2);
  EXPECT_EQ(at(19.0), 2);   // within one spacing beyond the top beam
  EXPECT_EQ(at(25.0), -1);  // too far outside the beams
  EXPECT_EQ(at(-25.0), -1);
}

TEST(Projection, BadPointsAreSkippedAndCounted) {
  const Config config = load_config(kConfig + "/vlp16.yaml");
  Scan scan;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  scan.points = {{nan, 0, 0}, {1, inf, 0}, {0.1f, 0, 0}, {500, 0, 0}, {10, 0, 0}};
  RangeImage image;
  RangeProjector(config.sensor).project(scan, image);
  EXPECT_EQ(image.stats().non_finite, 2);
  EXPECT_EQ(image.stats().out_of_range, 2);
  EXPECT_EQ(image.stats().projected, 1);
}

TEST(Projection, OnlyNanScanGivesEmptyResultAndAClearMessage) {
  const Config config = load_config(kConfig + "/kitti.yaml");
  Scan scan;
  scan.points.assign(1000, ScanPoint{std::numeric_limits<float>::quiet_NaN(), 0, 0});
  Segmenter segmenter(config.sensor, config.segmentation);
  SegmentationResult result;
  ASSERT_NO_THROW(segmenter.process(scan, result));
  EXPECT_EQ(result.image.stats().projected, 0);
  EXPECT_EQ(result.image.stats().non_finite, 1000);
  EXPECT_TRUE(result.cloud.points.empty());
  EXPECT_EQ(result.clusters.clusters(), 0);
  const std::string problem = projection_problem(result.image.stats());
  EXPECT_NE(problem.find("no valid point"), std::string::npos) << problem;
  EXPECT_NE(problem.find("1000 NaN/Inf"), std::string::npos) << problem;
}

TEST(Projection, RingSourceWithoutRingFieldIsAClearError) {
  Config config = load_config(kConfig + "/vlp16.yaml");
  config.sensor.row_source = RowSource::kRing;
  Scan scan;
  scan.points = {{10, 0, 0}};
  RangeImage image;
  try {
    RangeProjector(config.sensor).project(scan, image);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no ring field"), std::string::npos);
  }
}

TEST(Projection, DuplicateAzimuthTakesFreeNeighbourColumnWhateverTheOrder) {
  SensorParams sensor;
  sensor.rows = 1;
  sensor.columns = 360;
  sensor.ground_rows = 0;
  sensor.beam_angles_deg = {0.0};
  auto scan_of = [](std::vector<double> azimuths_deg) {
    Scan scan;
    for (double az_deg : azimuths_deg) {
      const double az = az_deg * M_PI / 180.0;
      scan.points.push_back({float(5 * std::cos(az)), float(5 * std::sin(az)), 0.f});
    }
    return scan;
  };
  // Four points in one 1-degree column and one far away. In azimuth order: the first keeps the
  // cell, the next (leaning right) takes the right neighbour, the third (right taken) the left
  // one, and the last finds no free neighbour.
  const Scan in_order = scan_of({10.3, 10.6, 10.7, 10.8, 50.0});
  const Scan shuffled = scan_of({50.0, 10.7, 10.3, 10.8, 10.6});
  RangeImage ordered_image, shuffled_image;
  RangeProjector(sensor).project(in_order, ordered_image);
  RangeProjector(sensor).project(shuffled, shuffled_image);
  const int col = static_cast<int>(10.5 + 180.0);
  for (const RangeImage* image : {&ordered_image, &shuffled_image}) {
    EXPECT_EQ(image->stats().projected, 4);
    EXPECT_EQ(image->stats().displaced, 2);
    EXPECT_EQ(image->stats().collisions, 1);
  }
  auto azimuth_at = [](const RangeImage& image, int cell) {
    const ScanPoint& p = image.point(cell);
    return std::atan2(p.y, p.x) * 180.0 / M_PI;
  };
  for (const RangeImage* image : {&ordered_image, &shuffled_image}) {
    EXPECT_NEAR(azimuth_at(*image, image->cell(0, col)), 10.3, 1e-4);
    EXPECT_NEAR(azimuth_at(*image, image->cell(0, col + 1)), 10.6, 1e-4);
    EXPECT_NEAR(azimuth_at(*image, image->cell(0, col - 1)), 10.7, 1e-4);
  }
}
