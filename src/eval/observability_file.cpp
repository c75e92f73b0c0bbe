#include "adaptive_lego_loam/eval/observability_file.h"

#include <cmath>

#include "adaptive_lego_loam/io/numeric_csv.h"
#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

const char* const kWhat = "the scan index and the 36 entries of its information matrix";

std::vector<TrueObservability> converted(const NumericCsv& table, const std::string& source) {
  std::vector<TrueObservability> scans;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const std::vector<double>& row = table.rows[i];
    const std::string place = source + ":" + std::to_string(table.lines[i]);
    const int previous = scans.empty() ? -1 : scans.back().frame;
    if (!(row[0] > previous) || row[0] != std::floor(row[0]) || row[0] > 1e9) {
      throw IoError(place + ": expected a scan index, an integer above " +
                    std::to_string(previous) + ", found " + std::to_string(row[0]));
    }
    TrueObservability& scan = scans.emplace_back();
    scan.frame = static_cast<int>(row[0]);
    for (int k = 0; k < 36; ++k) {
      if (!std::isfinite(row[k + 1])) {
        throw IoError(place + ": column " + std::to_string(k + 2) +
                      ": expected a finite information entry");
      }
      scan.information(k / 6, k % 6) = row[k + 1];
    }
  }
  if (scans.empty()) throw IoError(source + ": no scan: expected a line per scan (" + kWhat + ")");
  return scans;
}

}  // namespace

std::vector<TrueObservability> read_observability_csv(const std::string& path) {
  return converted(read_csv_numbers(path, 37, kWhat), path);
}

std::vector<TrueObservability> parse_observability_csv(const std::string& text,
                                                       const std::string& source) {
  return converted(parse_csv_numbers(text, source, 37, kWhat), source);
}

}  // namespace adaptive_lego_loam
