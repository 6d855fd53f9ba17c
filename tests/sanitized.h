// Test helper: kSanitized, whether this binary is built with AddressSanitizer. ASan replaces malloc
// and reserves terabytes of address space at start-up, so the tests of heap sizes and of
// address-space limits need a plain build and skip themselves under it.
#pragma once

namespace vgroove::testing_files {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
#else
inline constexpr bool kSanitized = false;
#endif

}  // namespace vgroove::testing_files
