#pragma once
// A saved map: a folder that run_sequence --save-map and map_optimization's save_map service
// write and that localization loads.
//
//   map.yaml                    what made it (config, sensor), counts, the files
//   global_map.pcd              every keyframe's features in the map frame, voxel-filtered
//   corner_map.pcd              the edges alone (the mapping's corner voxel)
//   surface_map.pcd             the surfaces alone (the mapping's surface voxel)
//   keyframe_poses_kitti.txt    each keyframe's sensor pose in the map frame (KITTI 3x4) ...
//   keyframe_poses_tum.txt      ... and with its stamp (TUM)
//   keyframes.csv               index, frame, stamp, degenerate, corner and surface points
//   keyframes/NNNNNN_corners.pcd, NNNNNN_surfaces.pcd
//                               each keyframe's features in its sensor frame (a keyframe merged
//                               into another has none)
//
// The PCD files are binary, fields x y z intensity (float32), readable by PCL and CloudCompare.

#include <string>
#include <vector>

#include "adaptive_lego_loam/core/common/params.h"
#include "adaptive_lego_loam/core/mapping/keyframe.h"

namespace adaptive_lego_loam {

struct MapDescription {
  std::string config;   // the config file the map was made with
  std::string sensor;   // its sensor.name
  std::string made_by;  // e.g. "run_sequence", "map_optimization"
  int frames = 0;       // scans that went into it
};

struct SavedMap {
  MapDescription description;
  std::vector<Keyframe> keyframes;  // index = position, poses in the map frame
};

// Throws IoError unless `dir` is free for a map: missing, an empty folder, or a saved map (which
// a new save replaces). Anything else there is never replaced.
void check_map_folder(const std::string& dir);

// Writes the map folder at `dir` atomically (io/atomic_files.h): a failed save leaves what was
// there. `global_voxel` 0 takes config.saved_map.voxel_size. Throws IoError naming the folder or
// file: a bad voxel size, `dir` not free (check_map_folder), a write that failed.
void save_map(const std::string& dir, const std::vector<Keyframe>& keyframes,
              const MapDescription& description, const Config& config, double global_voxel = 0.0);

// Reads a folder save_map wrote: keyframes.csv, the TUM poses and the keyframe clouds. Throws
// IoError naming the file, line and what was expected.
SavedMap load_map(const std::string& dir);

}  // namespace adaptive_lego_loam
