// A saved map: written and read back exactly (poses, stamps, clouds within the packing's grid),
// saved over an older map, never over anything else, and errors that name the folder.

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/map_files.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
using adaptive_lego_loam::test::error_of;
using adaptive_lego_loam::test::temp_path;
namespace fs = std::filesystem;

namespace {

Config vlp16_config() {
  return load_config(std::string(CONFIG_DIR) + "/vlp16.yaml");
}

// A wall of points 5 m ahead, in the keyframe's sensor frame.
PackedCloudPtr wall(int points, float height) {
  Cloud cloud;
  for (int i = 0; i < points; ++i) {
    CloudPoint p;
    p.x = 5.0f;
    p.y = -2.0f + 4.0f * i / points;
    p.z = height;
    p.intensity = static_cast<float>(i % 16);
    cloud.push_back(p);
  }
  return pack(cloud);
}

// `count` keyframes 1 m apart along x, turning 2 deg each; every third without clouds (merged).
std::vector<Keyframe> keyframes(int count) {
  std::vector<Keyframe> out;
  for (int i = 0; i < count; ++i) {
    Keyframe keyframe;
    keyframe.index = i;
    keyframe.frame = 3 * i;
    keyframe.stamp = 1e9 + 0.3 * i;
    keyframe.pose.translation() = Eigen::Vector3d(1.0 * i, 0.1 * i, 0.0);
    keyframe.pose.linear() =
        Eigen::AngleAxisd(0.035 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    keyframe.degenerate = i == 4;
    if (i % 3 != 2) {
      keyframe.corners = wall(50, 1.0f);
      keyframe.surfaces = wall(200, 0.0f);
    }
    out.push_back(keyframe);
  }
  return out;
}

MapDescription description() {
  return {"config/vlp16.yaml", "vlp16", "test_map_files", 30};
}

fs::path fresh(const std::string& name) {
  const fs::path dir = temp_path(name);
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST(MapFiles, SavedAndLoadedBackAsTheyWere) {
  const fs::path dir = fresh("map_round_trip");
  const std::vector<Keyframe> saved = keyframes(10);
  save_map(dir.string(), saved, description(), vlp16_config());
  const SavedMap loaded = load_map(dir.string());
  EXPECT_EQ(loaded.description.sensor, "vlp16");
  EXPECT_EQ(loaded.description.made_by, "test_map_files");
  EXPECT_EQ(loaded.description.frames, 30);
  ASSERT_EQ(loaded.keyframes.size(), saved.size());
  for (std::size_t i = 0; i < saved.size(); ++i) {
    const Keyframe& a = saved[i];
    const Keyframe& b = loaded.keyframes[i];
    EXPECT_EQ(b.index, a.index);
    EXPECT_EQ(b.frame, a.frame);
    EXPECT_NEAR(b.stamp, a.stamp, 1e-6);
    EXPECT_EQ(b.degenerate, a.degenerate);
    EXPECT_LT((b.pose.translation() - a.pose.translation()).norm(), 1e-6) << i;
    EXPECT_TRUE(b.pose.linear().isApprox(a.pose.linear(), 1e-6)) << i;
    ASSERT_EQ(b.has_clouds(), a.has_clouds()) << i;
    if (!a.has_clouds()) continue;
    ASSERT_EQ(b.surfaces->size(), a.surfaces->size());
    const CloudPtr original = a.surfaces->unpack(), read = b.surfaces->unpack();
    for (std::size_t j = 0; j < original->size(); ++j) {
      EXPECT_NEAR((*read)[j].y, (*original)[j].y, a.surfaces->step()) << i << ", " << j;
    }
  }
  // The global map in the map frame: keyframe 1's wall lies 5 m ahead of its pose.
  pcl::PointCloud<pcl::PointXYZI> global;
  ASSERT_EQ(pcl::io::loadPCDFile((dir / "global_map.pcd").string(), global), 0);
  EXPECT_GT(global.size(), 100u);
}

TEST(MapFiles, ASaveReplacesAnOlderMapAndATrailingSlashIsTheSameFolder) {
  // A parent of its own: other tests running at the same time save their maps beside theirs.
  const fs::path dir = fresh("map_replaced") / "map";
  fs::create_directories(dir.parent_path());
  save_map(dir.string(), keyframes(10), description(), vlp16_config());
  save_map(dir.string() + "/", keyframes(4), description(), vlp16_config());
  EXPECT_EQ(load_map(dir.string()).keyframes.size(), 4u);
  for (const auto& entry : fs::directory_iterator(dir.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

TEST(MapFiles, NeverSavedOverAFolderThatHoldsSomethingElse) {
  const fs::path dir = fresh("map_not_over_this");
  fs::create_directories(dir);
  std::ofstream(dir / "thesis.tex") << "keep\n";
  const std::string error =
      error_of([&] { save_map(dir.string(), keyframes(3), description(), vlp16_config()); });
  EXPECT_NE(error.find(dir.string() + ": a folder that holds no saved map"), std::string::npos)
      << error;
  EXPECT_TRUE(fs::exists(dir / "thesis.tex"));
  EXPECT_FALSE(fs::exists(dir / "map.yaml"));
  // Nor over a file, nor inside one.
  const fs::path file = temp_path("map_a_file.txt");
  std::ofstream(file) << "keep\n";
  EXPECT_NE(error_of([&] {
              save_map(file.string(), keyframes(3), description(), vlp16_config());
            }).find("a file is there"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              save_map((file / "map").string(), keyframes(3), description(), vlp16_config());
            }).find(file.string()),
            std::string::npos);
}

TEST(MapFiles, BadVoxelSizeAndNoKeyframesAreErrorsNamingTheFolder) {
  const fs::path dir = fresh("map_bad_request");
  EXPECT_NE(error_of([&] {
              save_map(dir.string(), keyframes(3), description(), vlp16_config(), 0.001);
            }).find("voxel size 0.001: expected 0 (the config's) or 0.01 to 10 m"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              save_map(dir.string(), {}, description(), vlp16_config());
            }).find(dir.string() + ": no keyframes to save yet"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir));
}

TEST(MapFiles, LoadingNamesTheFileAndWhatWasExpected) {
  const fs::path dir = fresh("map_broken");
  save_map(dir.string(), keyframes(5), description(), vlp16_config());
  std::ofstream(dir / "map.yaml") << "format: [1, 2]\n";
  EXPECT_NE(error_of([&] {
              load_map(dir.string());
            }).find((dir / "map.yaml").string() + ": format: expected"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load_map(temp_path("no_such_map")); }).find("not a saved map"),
            std::string::npos);
}
