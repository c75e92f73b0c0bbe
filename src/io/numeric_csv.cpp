#include "adaptive_lego_loam/io/numeric_csv.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"

namespace adaptive_lego_loam {
namespace {

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream stream(line);
  std::string cell;
  while (std::getline(stream, cell, ','))
    out.push_back(trimmed(cell));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

std::vector<double> numbers(const std::string& line, const std::string& place) {
  std::vector<double> row;
  for (const std::string& value : cells(line)) {
    char* end = nullptr;
    const double parsed = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size()) {
      throw IoError(place + ": column " + std::to_string(row.size() + 1) +
                    ": expected a number, found '" + value + "'");
    }
    row.push_back(parsed);
  }
  return row;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names)
    out += (out.empty() ? "" : ",") + name;
  return out;
}

// `columns` numbers a row; the header's names when `header` (and then its count), which must be
// `expected` unless that is empty.
NumericCsv parse(std::istream& input, const std::string& source, bool header,
                 std::optional<std::size_t> columns, const std::string& what,
                 const std::string& expected = "") {
  NumericCsv table;
  bool header_seen = !header;
  std::string line;
  for (int number = 1; std::getline(input, line); ++number) {
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#') continue;
    const std::string place = source + ":" + std::to_string(number);
    if (!header_seen) {
      table.columns = cells(text);
      if (!expected.empty() && joined(table.columns) != expected)
        throw IoError(place + ": expected the header " + expected);
      columns = table.columns.size();
      header_seen = true;
      continue;
    }
    std::vector<double> row = numbers(text, place);
    if (row.size() != *columns) {
      throw IoError(place + ": expected " + std::to_string(*columns) +
                    " comma-separated numbers (" + what + "), found " + std::to_string(row.size()));
    }
    table.rows.push_back(std::move(row));
    table.lines.push_back(number);
  }
  if (input.bad()) throw IoError(source + ": read failed");
  if (!header_seen) {
    throw IoError(source + ": empty: expected " +
                  (expected.empty() ? "a header line of column names" : "the header " + expected));
  }
  return table;
}

std::string header_what(const std::string& expected) {
  return expected.empty() ? "one for each column of the header" : expected;
}

std::ifstream opened(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw IoError(path + ": cannot open");
  return file;
}

}  // namespace

int NumericCsv::column(const std::string& name) const {
  const auto found = std::find(columns.begin(), columns.end(), name);
  return found == columns.end() ? -1 : static_cast<int>(found - columns.begin());
}

NumericCsv read_csv_with_header(const std::string& path, const std::string& expected) {
  std::ifstream file = opened(path);
  return parse(file, path, true, std::nullopt, header_what(expected), expected);
}

NumericCsv parse_csv_with_header(const std::string& text, const std::string& source,
                                 const std::string& expected) {
  std::istringstream input(text);
  return parse(input, source, true, std::nullopt, header_what(expected), expected);
}

NumericCsv read_csv_numbers(const std::string& path, std::size_t columns, const std::string& what) {
  std::ifstream file = opened(path);
  return parse(file, path, false, columns, what);
}

NumericCsv parse_csv_numbers(const std::string& text, const std::string& source,
                             std::size_t columns, const std::string& what) {
  std::istringstream input(text);
  return parse(input, source, false, columns, what);
}

}  // namespace adaptive_lego_loam
