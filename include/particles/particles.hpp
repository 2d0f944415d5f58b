#pragma once
/// @file
/// Everything particles offers a C++ program (docs/api.md): include this, link particles::particles.
#include <particles/choices.hpp>
#include <particles/errors.hpp>
#include <particles/golden.hpp>
#include <particles/renderer.hpp>
#include <particles/scenario.hpp>
#include <particles/simulation.hpp>
#include <particles/style.hpp>
#include <particles/version.hpp>
#include <particles/video_writer.hpp>
