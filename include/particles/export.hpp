#pragma once
// What libparticles.so shows its users: the classes and functions marked PARTICLES_API. The rest of
// the library is compiled with hidden visibility (CMakeLists.txt), so that nothing private can be
// linked against by accident and the library's own symbols cannot be interposed.

#if defined(__GNUC__) || defined(__clang__)
#define PARTICLES_API __attribute__((visibility("default")))
#else
#define PARTICLES_API
#endif
