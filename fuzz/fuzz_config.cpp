// The config loader (parse_config): the input is the YAML file. ConfigError is the answer to
// anything that is not a valid config; a config it returns passes validate().

#include "adaptive_lego_loam/core/common/params.h"
#include "fuzz_support.h"

using namespace adaptive_lego_loam;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Config config;
  try {
    config = parse_config(text, "fuzz.yaml");
  } catch (const ConfigError&) {
    return 0;
  }
  fuzz::check(static_cast<int>(config.sensor.beam_angles_deg.size()) == config.sensor.rows,
              "a loaded config has one beam angle per row");
  try {
    validate(config.sensor, "fuzz.yaml");
  } catch (const ConfigError&) {
    fuzz::check(false, "a loaded config passes validate()");
  }
  return 0;
}
