#pragma once
// How much slower this build runs than an ordinary one, for the few tests that bound a wall
// time to catch a quadratic blow-up (minutes, not seconds): AddressSanitizer and
// ThreadSanitizer builds run the engine 3 to 10 times slower.
namespace hapscene::test {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr double kSanitizerSlowdown = 5.0;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr double kSanitizerSlowdown = 5.0;
#else
inline constexpr double kSanitizerSlowdown = 1.0;
#endif
#else
inline constexpr double kSanitizerSlowdown = 1.0;
#endif

}  // namespace hapscene::test
