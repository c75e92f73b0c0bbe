#include "adaptive_lego_loam/io/scan_files.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "adaptive_lego_loam/io/io_error.h"
#include "adaptive_lego_loam/io/point_fields.h"

namespace adaptive_lego_loam {
namespace fs = std::filesystem;
namespace {

std::string read_file_bytes(const std::string& path, const std::string& what) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw IoError(path + ": cannot open " + what);
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError(path + ": cannot open " + what);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  if (file.bad()) throw IoError(path + ": read failed");
  return bytes.str();
}

// ---------------------------------------------------------------------------------------------
// PCD (v0.5 to v0.7): a text header up to the DATA line, then ascii, binary or binary_compressed
// records with the header's fields.

struct PcdHeader {
  std::vector<std::string> names;
  std::vector<uint32_t> sizes;  // bytes of one value
  std::vector<char> types;      // F, I or U
  std::vector<uint32_t> counts;
  std::optional<uint32_t> width, height, points;
  std::string data;                      // ascii, binary or binary_compressed
  std::size_t body = 0;                  // offset of the first byte after the DATA line
  int body_line = 0;                     // line number of the first body line
  std::vector<FieldDescription> fields;  // with offsets, from the lines above
  uint32_t point_step = 0;
};

struct PcdLayout {
  uint32_t width = 0;
  uint32_t height = 0;
  std::size_t points = 0;
};

// Records decoded from ascii or binary_compressed data, with their own field layout.
struct Records {
  std::vector<uint8_t> bytes;
  std::vector<FieldDescription> fields;
  uint32_t point_step = 0;
};

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::size_t start = line.find_first_not_of(" \t\r");
  while (start != std::string::npos) {
    const std::size_t end = line.find_first_of(" \t\r", start);
    words.push_back(line.substr(start, end - start));
    start = end == std::string::npos ? end : line.find_first_not_of(" \t\r", end);
  }
  return words;
}

uint32_t parse_unsigned(const std::string& word, const std::string& place, const std::string& key) {
  uint32_t value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) {
    throw IoError(place + ": " + key + " '" + word + "' is not an integer in [0, 4294967295]");
  }
  return value;
}

std::vector<uint32_t> parse_sizes(const std::vector<std::string>& words, const std::string& place) {
  std::vector<uint32_t> sizes;
  for (const std::string& word : words) {
    const uint32_t size = parse_unsigned(word, place, "SIZE");
    if (size != 1 && size != 2 && size != 4 && size != 8) {
      throw IoError(place + ": SIZE " + word + ": expected 1, 2, 4 or 8 bytes");
    }
    sizes.push_back(size);
  }
  return sizes;
}

std::vector<char> parse_types(const std::vector<std::string>& words, const std::string& place) {
  std::vector<char> types;
  for (const std::string& word : words) {
    if (word != "F" && word != "I" && word != "U") {
      throw IoError(place + ": TYPE '" + word + "': expected F, I or U");
    }
    types.push_back(word[0]);
  }
  return types;
}

std::vector<uint32_t> parse_counts(const std::vector<std::string>& words,
                                   const std::string& place) {
  std::vector<uint32_t> counts;
  for (const std::string& word : words) {
    const uint32_t count = parse_unsigned(word, place, "COUNT");
    if (count == 0) throw IoError(place + ": COUNT 0: expected at least 1 value per field");
    counts.push_back(count);
  }
  return counts;
}

uint32_t single_value(const std::vector<std::string>& values, const std::string& place,
                      const std::string& key) {
  if (values.size() != 1) {
    throw IoError(place + ": " + key + ": expected one number, found " +
                  std::to_string(values.size()));
  }
  return parse_unsigned(values[0], place, key);
}

// Fills `header` from one header line; returns false at the DATA line, the header's last.
bool read_header_line(const std::vector<std::string>& words, const std::string& place,
                      PcdHeader& header) {
  const std::string& key = words[0];
  const std::vector<std::string> values(words.begin() + 1, words.end());
  if (key == "VERSION" || key == "VIEWPOINT") {
    // nothing the reader needs
  } else if (key == "FIELDS" || key == "COLUMNS") {
    header.names = values;
  } else if (key == "SIZE") {
    header.sizes = parse_sizes(values, place);
  } else if (key == "TYPE") {
    header.types = parse_types(values, place);
  } else if (key == "COUNT") {
    header.counts = parse_counts(values, place);
  } else if (key == "WIDTH") {
    header.width = single_value(values, place, key);
  } else if (key == "HEIGHT") {
    header.height = single_value(values, place, key);
  } else if (key == "POINTS") {
    header.points = single_value(values, place, key);
  } else if (key == "DATA") {
    if (values.size() != 1) throw IoError(place + ": DATA: expected one word");
    header.data = values[0];
    return false;
  } else {
    throw IoError(place + ": unknown header line '" + key +
                  "'; expected VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT, VIEWPOINT, "
                  "POINTS or DATA");
  }
  return true;
}

// Same numbering as FieldType; 0 for a type that decode_points cannot read (8-byte integers).
uint8_t pcd_datatype(char type, uint32_t size) {
  if (type == 'F') return size == 4 ? 7 : size == 8 ? 8 : 0;
  if (size > 4) return 0;
  const uint8_t log2_size = size == 1 ? 0 : size == 2 ? 1 : 2;
  return static_cast<uint8_t>((type == 'I' ? 1 : 2) + 2 * log2_size);
}

void lay_out_fields(const std::string& source, PcdHeader& header) {
  const std::size_t n = header.names.size();
  if (n == 0) throw IoError(source + ": PCD header has no FIELDS line");
  if (header.counts.empty()) header.counts.assign(n, 1);
  const std::pair<const char*, std::size_t> lists[] = {{"SIZE", header.sizes.size()},
                                                       {"TYPE", header.types.size()},
                                                       {"COUNT", header.counts.size()}};
  for (const auto& [key, size] : lists) {
    if (size != n) {
      throw IoError(source + ": PCD header has " + std::to_string(size) + " " + key +
                    " entries for " + std::to_string(n) + " FIELDS");
    }
  }
  uint64_t offset = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (header.types[i] == 'F' && header.sizes[i] < 4) {
      throw IoError(source + ": PCD field '" + header.names[i] + "' has TYPE F and SIZE " +
                    std::to_string(header.sizes[i]) + "; expected SIZE 4 or 8");
    }
    header.fields.push_back({header.names[i], static_cast<uint32_t>(offset),
                             pcd_datatype(header.types[i], header.sizes[i]), header.counts[i]});
    offset += uint64_t{header.sizes[i]} * header.counts[i];
    if (offset > std::numeric_limits<uint32_t>::max()) {
      throw IoError(source + ": PCD fields add up to more than 4294967295 bytes a point");
    }
  }
  header.point_step = static_cast<uint32_t>(offset);
}

PcdHeader read_pcd_header(const std::string& bytes, const std::string& source) {
  PcdHeader header;
  std::size_t start = 0;
  int line_number = 1;
  bool more = true;
  for (; more && start < bytes.size(); ++line_number) {
    const std::size_t newline = bytes.find('\n', start);
    const std::size_t end = newline == std::string::npos ? bytes.size() : newline;
    const std::vector<std::string> words = split_words(bytes.substr(start, end - start));
    start = end == bytes.size() ? end : end + 1;
    if (words.empty() || words[0][0] == '#') continue;
    more = read_header_line(words, source + ":" + std::to_string(line_number), header);
  }
  if (more) throw IoError(source + ": PCD header has no DATA line");
  header.body = start;
  header.body_line = line_number;
  lay_out_fields(source, header);
  return header;
}

PcdLayout pcd_layout(const PcdHeader& header, const std::string& source) {
  if (!header.width && !header.points) {
    throw IoError(source + ": PCD header has neither WIDTH nor POINTS");
  }
  PcdLayout layout;
  layout.width = header.width.value_or(header.points.value_or(0));
  layout.height = header.height.value_or(1);
  layout.points = std::size_t{layout.width} * layout.height;
  if (header.points && *header.points != layout.points) {
    throw IoError(source + ": PCD header has POINTS " + std::to_string(*header.points) +
                  " but WIDTH x HEIGHT = " + std::to_string(layout.points));
  }
  return layout;
}

// The number of bytes `points` records of `point_step` take; throws when `available` is less.
std::size_t records_size(std::size_t points, uint32_t point_step, std::size_t available,
                         const std::string& source, const std::string& what) {
  std::size_t size = 0;
  if (__builtin_mul_overflow(points, std::size_t{point_step}, &size) || size > available) {
    throw IoError(source + ": " + what + " holds " + std::to_string(available) +
                  " bytes, expected " + std::to_string(points) + " points x " +
                  std::to_string(point_step) + " bytes");
  }
  return size;
}

// ---------------------------------------------------------------------------------------------
// PCD bodies: each returns the records, `points` x `point_step` bytes, little endian.

template <typename T>
bool parse_integer(const std::string& word, uint8_t* out) {
  T value{};
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) return false;
  std::memcpy(out, &value, sizeof(T));
  return true;
}

template <typename T>
bool parse_real(const std::string& word, uint8_t* out) {
  char* end = nullptr;
  const T value = static_cast<T>(std::strtod(word.c_str(), &end));
  if (word.empty() || end != word.c_str() + word.size()) return false;
  std::memcpy(out, &value, sizeof(T));
  return true;
}

// One ASCII value into the bytes of its type.
bool parse_ascii_value(const std::string& word, char type, uint32_t size, uint8_t* out) {
  if (type == 'F') return size == 8 ? parse_real<double>(word, out) : parse_real<float>(word, out);
  const bool is_signed = type == 'I';
  switch (size) {
    case 1:
      return is_signed ? parse_integer<int8_t>(word, out) : parse_integer<uint8_t>(word, out);
    case 2:
      return is_signed ? parse_integer<int16_t>(word, out) : parse_integer<uint16_t>(word, out);
    case 4:
      return is_signed ? parse_integer<int32_t>(word, out) : parse_integer<uint32_t>(word, out);
    default:
      return is_signed ? parse_integer<int64_t>(word, out) : parse_integer<uint64_t>(word, out);
  }
}

void parse_ascii_record(const std::vector<std::string>& words, const PcdHeader& header,
                        const std::string& place, uint8_t* record) {
  std::size_t word = 0;
  for (std::size_t f = 0; f < header.fields.size(); ++f) {
    const uint32_t size = header.sizes[f];
    for (uint32_t k = 0; k < header.counts[f]; ++k, ++word) {
      uint8_t* out = record + header.fields[f].offset + std::size_t{k} * size;
      if (!parse_ascii_value(words[word], header.types[f], size, out)) {
        throw IoError(place + ": field '" + header.names[f] + "': '" + words[word] + "' is not a " +
                      std::string(1, header.types[f]) + std::to_string(size) + " value");
      }
    }
  }
}

// Records grow with the lines actually read, so a header cannot make us allocate more than the
// text holds.
Records read_ascii_body(const std::string& bytes, const PcdHeader& header, std::size_t points,
                        const std::string& source) {
  std::size_t values = 0;
  for (uint32_t count : header.counts)
    values += count;
  Records records{{}, header.fields, header.point_step};
  std::size_t read = 0;
  std::size_t start = header.body;
  for (int line_number = header.body_line; start < bytes.size(); ++line_number) {
    const std::size_t newline = bytes.find('\n', start);
    const std::size_t end = newline == std::string::npos ? bytes.size() : newline;
    const std::vector<std::string> words = split_words(bytes.substr(start, end - start));
    start = end == bytes.size() ? end : end + 1;
    if (words.empty()) continue;
    const std::string place = source + ":" + std::to_string(line_number);
    if (read == points)
      throw IoError(place + ": more points than the header's " + std::to_string(points));
    if (words.size() != values) {
      throw IoError(place + ": expected " + std::to_string(values) + " values, found " +
                    std::to_string(words.size()));
    }
    records.bytes.resize(records.bytes.size() + header.point_step);
    parse_ascii_record(words, header, place, records.bytes.data() + read * header.point_step);
    ++read;
  }
  if (read != points) {
    throw IoError(source + ": PCD data holds " + std::to_string(read) + " points, expected " +
                  std::to_string(points));
  }
  return records;
}

uint32_t load_le32(const uint8_t* at) {
  return uint32_t{at[0]} | uint32_t{at[1]} << 8 | uint32_t{at[2]} << 16 | uint32_t{at[3]} << 24;
}

// liblzf's format, as PCL writes it: a control byte below 32 starts a run of control + 1
// literal bytes; any other is a back reference of length (control >> 5) + 2 (7 meaning: add
// the next byte) at distance ((control & 31) << 8) + next byte + 1. Returns false on a
// malformed stream or one that does not fill `out` exactly.
bool lzf_decompress(const uint8_t* in, std::size_t in_size, std::vector<uint8_t>& out) {
  std::size_t ip = 0, op = 0;
  while (ip < in_size) {
    const unsigned control = in[ip++];
    if (control < 32) {
      const std::size_t length = control + 1;
      if (length > in_size - ip || length > out.size() - op) return false;
      std::memcpy(out.data() + op, in + ip, length);
      ip += length;
      op += length;
      continue;
    }
    std::size_t length = control >> 5;
    if (ip >= in_size) return false;
    if (length == 7) {
      length += in[ip++];
      if (ip >= in_size) return false;
    }
    const std::size_t distance = ((control & 31) << 8) + in[ip++] + 1;
    length += 2;
    if (distance > op || length > out.size() - op) return false;
    for (std::size_t i = 0; i < length; ++i, ++op)  // may overlap: byte by byte
      out[op] = out[op - distance];
  }
  return op == out.size();
}

// LZF turns a 3-byte back reference into at most 264 bytes.
constexpr std::size_t kLzfMaxExpansion = 88;

// PCL leaves padding fields ("_") out of compressed data.
bool is_padding(const PcdHeader& header, std::size_t field) {
  return header.names[field] == "_";
}

std::size_t field_bytes(const PcdHeader& header, std::size_t field) {
  return std::size_t{header.sizes[field]} * header.counts[field];
}

// binary_compressed: compressed size and uncompressed size (uint32 each), then the LZF stream
// of the records stored field by field (all x, then all y, ...).
Records read_compressed_body(const std::string& bytes, const PcdHeader& header, std::size_t points,
                             const std::string& source) {
  const auto* body = reinterpret_cast<const uint8_t*>(bytes.data()) + header.body;
  const std::size_t available = bytes.size() - header.body;
  if (available < 8) throw IoError(source + ": PCD compressed data has no size words");
  const uint32_t compressed = load_le32(body);
  const uint32_t uncompressed = load_le32(body + 4);
  if (compressed > available - 8) {
    throw IoError(source + ": PCD compressed size " + std::to_string(compressed) +
                  " runs past the end of the file (" + std::to_string(available - 8) +
                  " bytes left)");
  }
  std::size_t point_bytes = 0;
  for (std::size_t f = 0; f < header.fields.size(); ++f)
    point_bytes += is_padding(header, f) ? 0 : field_bytes(header, f);
  std::size_t expected = 0;
  if (__builtin_mul_overflow(points, point_bytes, &expected) || uncompressed != expected) {
    throw IoError(source + ": PCD uncompressed size " + std::to_string(uncompressed) +
                  ", expected " + std::to_string(points) + " points x " +
                  std::to_string(point_bytes) + " bytes");
  }
  if (uncompressed > std::size_t{compressed} * kLzfMaxExpansion) {
    throw IoError(source + ": PCD compressed size " + std::to_string(compressed) +
                  " is too small for " + std::to_string(uncompressed) + " bytes of LZF data");
  }
  std::vector<uint8_t> by_field(uncompressed);
  if (!lzf_decompress(body + 8, compressed, by_field)) {
    throw IoError(source + ": PCD compressed data is not a valid LZF stream of " +
                  std::to_string(uncompressed) + " bytes");
  }
  // The records without the padding, which need not be stored (nor allocated).
  Records records;
  records.bytes.resize(uncompressed);
  records.point_step = static_cast<uint32_t>(point_bytes);
  std::size_t column = 0, offset = 0;
  for (std::size_t f = 0; f < header.fields.size(); ++f) {
    if (is_padding(header, f)) continue;
    const std::size_t size = field_bytes(header, f);
    records.fields.push_back(header.fields[f]);
    records.fields.back().offset = static_cast<uint32_t>(offset);
    for (std::size_t i = 0; i < points; ++i, column += size) {
      std::memcpy(records.bytes.data() + i * point_bytes + offset, by_field.data() + column, size);
    }
    offset += size;
  }
  return records;
}

}  // namespace

Scan parse_kitti_bin(const std::string& bytes, const std::string& source) {
  if (bytes.size() % 16 != 0) {
    throw IoError(source + ": size " + std::to_string(bytes.size()) +
                  " bytes is not a multiple of 16 (float32 x, y, z, reflectance per point)");
  }
  Scan scan;
  scan.points.resize(bytes.size() / 16);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    float values[4];
    std::memcpy(values, bytes.data() + 16 * i, sizeof(values));
    scan.points[i].x = values[0];
    scan.points[i].y = values[1];
    scan.points[i].z = values[2];
    scan.points[i].intensity = values[3];
  }
  return scan;
}

Scan read_kitti_bin(const std::string& path) {
  return parse_kitti_bin(read_file_bytes(path, "KITTI scan"), path);
}

void write_kitti_bin(const std::string& path, const Scan& scan) {
  std::vector<float> values;
  values.reserve(scan.points.size() * 4);
  for (const ScanPoint& p : scan.points) {
    values.insert(values.end(), {p.x, p.y, p.z, p.intensity});
  }
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw IoError(path + ": cannot open for writing");
  file.write(reinterpret_cast<const char*>(values.data()),
             static_cast<std::streamsize>(values.size() * sizeof(float)));
  if (!file) throw IoError(path + ": write failed");
}

Scan parse_pcd(const std::string& bytes, const std::string& source, const DecodeOptions& options) {
  const PcdHeader header = read_pcd_header(bytes, source);
  const PcdLayout layout = pcd_layout(header, source);
  PackedPoints packed;
  packed.width = layout.width;
  packed.height = layout.height;
  Records records;
  if (header.data == "binary") {
    packed.fields = header.fields;
    packed.point_step = header.point_step;
    packed.data = reinterpret_cast<const uint8_t*>(bytes.data()) + header.body;
    packed.data_size = records_size(layout.points, header.point_step, bytes.size() - header.body,
                                    source, "PCD binary data");
    return decode_points(packed, source, options);
  }
  if (header.data == "ascii") {
    records = read_ascii_body(bytes, header, layout.points, source);
  } else if (header.data == "binary_compressed") {
    records = read_compressed_body(bytes, header, layout.points, source);
  } else {
    throw IoError(source + ": PCD DATA '" + header.data +
                  "': expected ascii, binary or binary_compressed");
  }
  packed.fields = records.fields;
  packed.point_step = records.point_step;
  packed.data = records.bytes.data();
  packed.data_size = records.bytes.size();
  return decode_points(packed, source, options);
}

Scan read_pcd(const std::string& path, const DecodeOptions& options) {
  return parse_pcd(read_file_bytes(path, "PCD file"), path, options);
}

Scan read_scan_file(const std::string& path, const DecodeOptions& options) {
  const std::string extension = fs::path(path).extension().string();
  if (extension == ".bin") return read_kitti_bin(path);
  if (extension == ".pcd") return read_pcd(path, options);
  throw IoError(path + ": unknown scan file type '" + extension + "'; expected .bin or .pcd");
}

std::vector<std::string> list_scan_files(const std::string& dir) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) throw IoError(dir + ": not a directory");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() && (extension == ".bin" || extension == ".pcd")) {
      files.push_back(entry.path().string());
    }
  }
  if (error) throw IoError(dir + ": cannot list: " + error.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace adaptive_lego_loam
