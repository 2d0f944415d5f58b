#pragma once
/// @file
/// What libparticles.so shows its users: the classes and functions marked PARTICLES_API. The rest of
/// the library is compiled with hidden visibility (CMakeLists.txt), so that nothing private can be
/// linked against by accident and the library's own symbols cannot be interposed.

/// Every public header includes this one: a compiler in an older mode says what it needs here, once,
/// instead of failing on std::span a few lines later. (MSVC reports __cplusplus as 199711L unless
/// /Zc:__cplusplus; _MSVC_LANG is its real value.)
#if defined(_MSVC_LANG)
#define PARTICLES_CPLUSPLUS _MSVC_LANG
#else
#define PARTICLES_CPLUSPLUS __cplusplus
#endif
#if PARTICLES_CPLUSPLUS < 202002L
#error \
    "particles' headers need C++20: compile with -std=c++20 (CMake: the particles::particles target sets it; pkg-config: its --cflags carry it)"
#endif

#if defined(__GNUC__) || defined(__clang__)
#define PARTICLES_API __attribute__((visibility("default")))
#else
#define PARTICLES_API
#endif
