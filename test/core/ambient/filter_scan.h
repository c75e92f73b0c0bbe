#pragma once
// One scan through a new ambient filter.

#include "adaptive_lego_loam/core/ambient/ambient_filter.h"

namespace adaptive_lego_loam::test {

inline AmbientFilterResult filter(const Config& config, const Scan& scan) {
  AmbientFilter ambient(config);
  AmbientFilterResult result;
  ambient.process(scan, result);
  return result;
}

}  // namespace adaptive_lego_loam::test
