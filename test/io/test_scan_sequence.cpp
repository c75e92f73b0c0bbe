// Folders of scans as sequences: stamps from a KITTI times.txt, else a scan period apart.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "adaptive_lego_loam/io/scan_sequence.h"
#include "support/temp_files.h"

using namespace adaptive_lego_loam;
namespace fs = std::filesystem;

TEST(ScanSequence, StampsFromTimesTxtElseAScanPeriodApart) {
  const std::string kitti = std::string(TEST_DATA_DIR) + "/kitti_seq07";
  EXPECT_TRUE(folder_has_times(kitti));
  const auto sequence = open_folder_sequence(kitti, 0.05);
  sequence->next();
  sequence->next();
  EXPECT_DOUBLE_EQ(*sequence->last_stamp(), 0.1038752);  // times.txt, whatever the period

  const fs::path folder = test::temp_path("pcd_sequence");
  fs::remove_all(folder);
  fs::create_directories(folder);
  for (const char* name : {"a.pcd", "b.pcd", "c.pcd"}) {
    std::ofstream(folder / name) << "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n"
                                    "1 2 3\n";
  }
  EXPECT_FALSE(folder_has_times(folder.string()));
  const auto at_20_hz = open_folder_sequence(folder.string(), 0.05);
  std::vector<double> stamps;
  while (at_20_hz->next())
    stamps.push_back(*at_20_hz->last_stamp());
  EXPECT_EQ(stamps, (std::vector<double>{0.0, 0.05, 0.1}));
}
