#pragma once
// Which sanitizer the tests are built with: scripts/test runs them under AddressSanitizer +
// UndefinedBehaviorSanitizer (build-asan) and the core's under ThreadSanitizer (build-tsan), each
// several times slower than the plain build, so the costliest tests take fewer steps there. GCC
// says so by a macro, clang by __has_feature.

#ifdef __has_feature
#define PARTICLES_TEST_HAS_FEATURE(name) __has_feature(name)
#else
#define PARTICLES_TEST_HAS_FEATURE(name) 0
#endif

namespace particles::test {

inline constexpr bool kUnderAddressSanitizer =
#if defined(__SANITIZE_ADDRESS__) || PARTICLES_TEST_HAS_FEATURE(address_sanitizer)
    true;
#else
    false;
#endif

inline constexpr bool kUnderThreadSanitizer =
#if defined(__SANITIZE_THREAD__) || PARTICLES_TEST_HAS_FEATURE(thread_sanitizer)
    true;
#else
    false;
#endif

inline constexpr bool kUnderSanitizer = kUnderAddressSanitizer || kUnderThreadSanitizer;

}  // namespace particles::test
