#pragma once
// What the fuzz targets share: reading structured values off the front of the input, and
// checking a property the reader promises (a failed check is a finding, like a crash).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace adaptive_lego_loam::fuzz {

// Little-endian values from the front of the input; past its end every value reads as zero, so
// that any input is a valid message.
class ByteReader {
 public:
  ByteReader(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  template <typename T>
  T next() {
    T value{};
    uint8_t bytes[sizeof(T)] = {};
    const std::size_t take = std::min(sizeof(T), size_ - used_);
    std::memcpy(bytes, data_ + used_, take);
    used_ += take;
    for (std::size_t i = sizeof(T); i-- > 0;)
      value = static_cast<T>((static_cast<uint64_t>(value) << 8) | bytes[i]);
    return value;
  }

  std::string text(std::size_t length) {
    const std::size_t take = std::min(length, size_ - used_);
    std::string result(reinterpret_cast<const char*>(data_ + used_), take);
    used_ += take;
    return result;
  }

  std::string rest() { return text(size_ - used_); }

 private:
  const uint8_t* data_;
  std::size_t size_;
  std::size_t used_ = 0;
};

inline void check(bool holds, const char* property) {
  if (holds) return;
  std::fprintf(stderr, "fuzz: property violated: %s\n", property);
  std::abort();
}

}  // namespace adaptive_lego_loam::fuzz
