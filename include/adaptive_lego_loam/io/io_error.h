#pragma once

#include <stdexcept>

namespace adaptive_lego_loam {

// A file or message that cannot be read as expected. The message names the file (or topic), the
// field and what was expected.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace adaptive_lego_loam
