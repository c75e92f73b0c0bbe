#pragma once
// Comma-separated numbers as the tools write them (run_sequence's degeneration.csv, lidar_sim's
// observability.csv, the motion sensors' imu.csv and wheel_odom.csv): lines starting with '#' and
// blank lines are skipped, then either a header of column names or none, then rows of numbers (nan
// and inf read as such). Bad input throws IoError as "<source>:<line>: <what was expected>".

#include <string>
#include <vector>

namespace adaptive_lego_loam {

struct NumericCsv {
  std::vector<std::string> columns;  // the header's names (empty without a header)
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;  // each row's line number in the file, for messages
  // The index of a column by name, or -1.
  int column(const std::string& name) const;
};

// With a header: every row has as many numbers as it has names. A non-empty `expected` is the
// header the file must have (its names joined by commas; spaces around them do not count).
NumericCsv read_csv_with_header(const std::string& path, const std::string& expected = "");
NumericCsv parse_csv_with_header(const std::string& text, const std::string& source,
                                 const std::string& expected = "");

// Without a header: every row has `columns` numbers, `what` says what they are (for messages).
NumericCsv read_csv_numbers(const std::string& path, std::size_t columns, const std::string& what);
NumericCsv parse_csv_numbers(const std::string& text, const std::string& source,
                             std::size_t columns, const std::string& what);

}  // namespace adaptive_lego_loam
