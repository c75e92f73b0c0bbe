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

// PCD files of the drivers' fields read as from a bag: a legacy OS1's t (a share of the sweep)
// with the sequence's period, Hesai's absolute timestamp as offsets.
TEST(ScanSequence, PcdFilesTimesAsTheDriversWroteThem) {
  const fs::path folder = test::temp_path("driver_pcds");
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "0_os1.pcd") << "FIELDS x y z t ring\nSIZE 4 4 4 4 1\nTYPE F F F F U\n"
                                         "WIDTH 2\nDATA ascii\n1 2 3 0 5\n4 5 6 0.5 6\n";
  std::ofstream(folder / "1_hesai.pcd")
      << "FIELDS x y z timestamp ring\nSIZE 4 4 4 8 2\nTYPE F F F F U\nWIDTH 2\nDATA ascii\n"
         "1 2 3 1712345678.25 5\n4 5 6 1712345678.275 6\n";
  const auto sequence = open_folder_sequence(folder.string(), 0.05);
  const Scan os1 = *sequence->next();
  ASSERT_TRUE(os1.has_time);
  EXPECT_FLOAT_EQ(os1.points[1].time, 0.025f);
  const Scan hesai = *sequence->next();
  ASSERT_TRUE(hesai.has_time);
  EXPECT_EQ(hesai.points[0].time, 0.f);
  EXPECT_NEAR(hesai.points[1].time, 0.025f, 1e-6);
}
