#include "adaptive_lego_loam/io/map_files.h"

#include <pcl/io/pcd_io.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "adaptive_lego_loam/core/mapping/map_assembly.h"
#include "adaptive_lego_loam/io/atomic_files.h"
#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/pose_files.h"

namespace adaptive_lego_loam {
namespace fs = std::filesystem;
namespace {

constexpr const char* kFormat = "adaptive_lego_loam map 1";
constexpr const char* kKeyframesHeader = "index,frame,stamp,degenerate,corners,surfaces";

std::string cloud_name(int index, const char* layer) {
  char name[64];
  std::snprintf(name, sizeof(name), "%06d_%s.pcd", index, layer);
  return (fs::path("keyframes") / name).string();
}

void write_pcd(const std::string& path, const Cloud& cloud) {
  // PCL refuses to write an empty cloud; an empty layer is still a valid file.
  if (cloud.empty()) {
    std::ofstream file(path);
    file << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n"
            "SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 0\nHEIGHT 1\n"
            "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA ascii\n";
    if (!file) throw IoError(path + ": cannot write");
    return;
  }
  if (pcl::io::savePCDFileBinary(path, cloud) != 0) throw IoError(path + ": cannot write");
}

CloudPtr read_pcd_cloud(const std::string& path) {
  CloudPtr cloud(new Cloud);
  if (!fs::exists(path)) throw IoError(path + ": missing (keyframes.csv lists its points)");
  if (pcl::io::loadPCDFile(path, *cloud) != 0) {
    throw IoError(path + ": not a readable PCD file with fields x y z intensity");
  }
  return cloud;
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

double path_length(const std::vector<Keyframe>& keyframes) {
  double length = 0.0;
  for (std::size_t i = 1; i < keyframes.size(); ++i)
    length += (keyframes[i].pose.translation() - keyframes[i - 1].pose.translation()).norm();
  return length;
}

void write_keyframes(const std::string& dir, const std::vector<Keyframe>& keyframes) {
  fs::create_directories(fs::path(dir) / "keyframes");
  std::ofstream list(fs::path(dir) / "keyframes.csv");
  list << kKeyframesHeader << "\n";
  std::vector<double> stamps;
  std::vector<Eigen::Isometry3d> poses;
  for (const Keyframe& keyframe : keyframes) {
    const std::size_t corners = keyframe.has_clouds() ? keyframe.corners->size() : 0;
    const std::size_t surfaces = keyframe.has_clouds() ? keyframe.surfaces->size() : 0;
    char stamp[32];
    std::snprintf(stamp, sizeof(stamp), "%.9f", keyframe.stamp);
    list << keyframe.index << "," << keyframe.frame << "," << stamp << ","
         << int(keyframe.degenerate) << "," << corners << "," << surfaces << "\n";
    if (corners > 0) {
      write_pcd((fs::path(dir) / cloud_name(keyframe.index, "corners")).string(),
                *keyframe.corners->unpack());
    }
    if (surfaces > 0) {
      write_pcd((fs::path(dir) / cloud_name(keyframe.index, "surfaces")).string(),
                *keyframe.surfaces->unpack());
    }
    stamps.push_back(keyframe.stamp);
    poses.push_back(keyframe.pose);
  }
  if (!list) throw IoError(dir + "/keyframes.csv: cannot write");
  write_kitti_poses((fs::path(dir) / "keyframe_poses_kitti.txt").string(), poses);
  write_tum_poses((fs::path(dir) / "keyframe_poses_tum.txt").string(), stamps, poses);
}

YAML::Node layer_entry(const std::string& dir, const char* file, const Cloud& cloud, double leaf) {
  write_pcd((fs::path(dir) / file).string(), cloud);
  YAML::Node entry;
  entry["file"] = file;
  entry["points"] = cloud.size();
  entry["voxel_size"] = leaf;
  return entry;
}

void write_description(const std::string& dir, const std::vector<Keyframe>& keyframes,
                       const MapDescription& description, YAML::Node layers) {
  YAML::Node yaml;
  yaml["format"] = kFormat;
  yaml["made_by"] = description.made_by;
  yaml["created"] = utc_now();
  yaml["config"] = description.config;
  yaml["sensor"] = description.sensor;
  yaml["frames"] = description.frames;
  yaml["keyframes"] = keyframes.size();
  int with_clouds = 0;
  for (const Keyframe& keyframe : keyframes)
    with_clouds += keyframe.has_clouds();
  yaml["keyframes_with_clouds"] = with_clouds;
  yaml["path_length_m"] = path_length(keyframes);
  for (const auto& layer : layers)
    yaml[layer.first.as<std::string>()] = layer.second;
  std::ofstream file(fs::path(dir) / "map.yaml");
  file << yaml << "\n";
  if (!file) throw IoError(dir + "/map.yaml: cannot write");
}

MapDescription read_description(const std::string& dir) {
  const std::string path = (fs::path(dir) / "map.yaml").string();
  if (!fs::exists(path)) throw IoError(dir + ": not a saved map (no map.yaml)");
  YAML::Node yaml;
  try {
    yaml = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw IoError(path + ": not valid YAML: " + e.what());
  }
  if (!yaml.IsMap() || !yaml["format"] || !yaml["format"].IsScalar() ||
      yaml["format"].Scalar() != kFormat) {
    throw IoError(path + ": format: expected \"" + std::string(kFormat) + "\"");
  }
  MapDescription description;
  const auto text = [&](const char* key) {
    return yaml[key] && yaml[key].IsScalar() ? yaml[key].as<std::string>() : std::string();
  };
  description.config = text("config");
  description.sensor = text("sensor");
  description.made_by = text("made_by");
  description.frames = yaml["frames"] ? yaml["frames"].as<int>(0) : 0;
  return description;
}

// One line of keyframes.csv: index,frame,stamp,degenerate,corners,surfaces.
struct KeyframeEntry {
  Keyframe keyframe;
  long corners = 0, surfaces = 0;  // points in its cloud files
};

KeyframeEntry parse_keyframe(const std::string& line, const std::string& where,
                             int expected_index) {
  std::istringstream fields(line);
  KeyframeEntry entry;
  Keyframe& keyframe = entry.keyframe;
  char c1 = 0, c2 = 0, c3 = 0, c4 = 0, c5 = 0;
  int degenerate = 0;
  fields >> keyframe.index >> c1 >> keyframe.frame >> c2 >> keyframe.stamp >> c3 >> degenerate >>
      c4 >> entry.corners >> c5 >> entry.surfaces;
  if (!fields || c1 != ',' || c2 != ',' || c3 != ',' || c4 != ',' || c5 != ',' ||
      !(fields >> std::ws).eof() || entry.corners < 0 || entry.surfaces < 0) {
    throw IoError(where + ": expected " + std::string(kKeyframesHeader));
  }
  if (keyframe.index != expected_index) {
    throw IoError(where + ": index: expected " + std::to_string(expected_index));
  }
  keyframe.degenerate = degenerate != 0;
  return entry;
}

// A keyframe's layer: read when the list says it has points, else empty.
PackedCloudPtr read_layer(const std::string& dir, const KeyframeEntry& entry, const char* layer,
                          long points) {
  if (points == 0) return pack(Cloud());
  const std::string path = (fs::path(dir) / cloud_name(entry.keyframe.index, layer)).string();
  const CloudPtr cloud = read_pcd_cloud(path);
  if (static_cast<long>(cloud->size()) != points) {
    throw IoError(path + ": expected " + std::to_string(points) +
                  " points (keyframes.csv), found " + std::to_string(cloud->size()));
  }
  return pack(*cloud);
}

std::vector<KeyframeEntry> read_keyframes(const std::string& dir) {
  const std::string path = (fs::path(dir) / "keyframes.csv").string();
  std::ifstream file(path);
  if (!file) throw IoError(path + ": missing");
  std::string line;
  if (!std::getline(file, line) || line != kKeyframesHeader) {
    throw IoError(path + ":1: expected the header " + std::string(kKeyframesHeader));
  }
  std::vector<KeyframeEntry> entries;
  for (int number = 2; std::getline(file, line); ++number) {
    if (line.empty()) continue;
    entries.push_back(parse_keyframe(line, path + ":" + std::to_string(number),
                                     static_cast<int>(entries.size())));
  }
  if (entries.empty()) throw IoError(path + ": no keyframes");
  return entries;
}

}  // namespace

void check_map_folder(const std::string& dir) {
  fs::path path = fs::path(dir).lexically_normal();
  if (!path.has_filename()) path = path.parent_path();
  std::error_code error;
  if (!fs::exists(path, error)) return;
  if (!fs::is_directory(path, error)) {
    throw IoError(dir +
                  ": a file is there: a map is saved only in a new or empty folder or over "
                  "a saved map");
  }
  if (fs::is_empty(path, error) || fs::exists(path / "map.yaml", error)) return;
  throw IoError(dir +
                ": a folder that holds no saved map (no map.yaml): a map is saved only in a "
                "new or empty folder or over a saved map");
}

void save_map(const std::string& dir, const std::vector<Keyframe>& keyframes,
              const MapDescription& description, const Config& config, double global_voxel) {
  if (keyframes.empty()) throw IoError(dir + ": no keyframes to save yet");
  constexpr double kMin = SavedMapParams::kMinVoxel, kMax = SavedMapParams::kMaxVoxel;
  if (!(global_voxel == 0.0 || (global_voxel >= kMin && global_voxel <= kMax))) {
    char text[160];
    std::snprintf(text, sizeof(text), ": voxel size %g: expected 0 (the config's) or %g to %g m",
                  global_voxel, kMin, kMax);
    throw IoError(dir + text);
  }
  check_map_folder(dir);
  const double leaf = global_voxel > 0.0 ? global_voxel : config.saved_map.voxel_size;
  write_atomically(dir, [&](const std::string& folder) {
    std::error_code error;
    fs::create_directories(folder, error);
    if (error) throw IoError(dir + ": cannot make the map's folder: " + error.message());
    write_keyframes(folder, keyframes);
    YAML::Node layers;
    layers["global_map"] =
        layer_entry(folder, "global_map.pcd", *assemble_map(keyframes, MapLayer::kAll, leaf), leaf);
    layers["corner_map"] =
        layer_entry(folder, "corner_map.pcd",
                    *assemble_map(keyframes, MapLayer::kCorners, config.mapping.corner_voxel),
                    config.mapping.corner_voxel);
    layers["surface_map"] =
        layer_entry(folder, "surface_map.pcd",
                    *assemble_map(keyframes, MapLayer::kSurfaces, config.mapping.surface_voxel),
                    config.mapping.surface_voxel);
    write_description(folder, keyframes, description, layers);
  });
}

SavedMap load_map(const std::string& dir) {
  SavedMap map;
  map.description = read_description(dir);
  const std::vector<KeyframeEntry> entries = read_keyframes(dir);
  const std::string poses_path = (fs::path(dir) / "keyframe_poses_tum.txt").string();
  const StampedPoses poses = read_tum_poses(poses_path);
  if (poses.poses.size() != entries.size()) {
    throw IoError(poses_path + ": expected " + std::to_string(entries.size()) +
                  " poses (keyframes.csv), found " + std::to_string(poses.poses.size()));
  }
  for (const KeyframeEntry& entry : entries) {
    Keyframe keyframe = entry.keyframe;
    keyframe.pose = poses.poses[keyframe.index];
    if (entry.corners + entry.surfaces > 0) {
      keyframe.corners = read_layer(dir, entry, "corners", entry.corners);
      keyframe.surfaces = read_layer(dir, entry, "surfaces", entry.surfaces);
    }
    map.keyframes.push_back(std::move(keyframe));
  }
  return map;
}

}  // namespace adaptive_lego_loam
