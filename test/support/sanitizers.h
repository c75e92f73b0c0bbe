#pragma once
// Whether this test was built with AddressSanitizer (scripts/test.sh --sanitize). The sanitized
// build runs 7-13 x slower; tests that measure accuracy over drives of hundreds of scans skip
// there (the optimized build measures it) and keep the sanitizer's check on shorter drives.

namespace adaptive_lego_loam::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kBuiltWithSanitizers = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kBuiltWithSanitizers = true;
#else
inline constexpr bool kBuiltWithSanitizers = false;
#endif
#else
inline constexpr bool kBuiltWithSanitizers = false;
#endif

}  // namespace adaptive_lego_loam::test

// Skips the calling test in the sanitized build, saying why.
#define ALEGO_SKIP_WHEN_SANITIZED()                                                          \
  if (adaptive_lego_loam::test::kBuiltWithSanitizers)                                        \
  GTEST_SKIP() << "an accuracy measurement over a long drive: the optimized build runs it, " \
                  "the sanitized one checks the same code on shorter drives"
