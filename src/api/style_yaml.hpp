#pragma once
// A particles::Style (include/particles/style.hpp) written as the style file it mirrors, for the
// scenario loader's style-file path (scenario::StyleFile): so that a Style is merged and checked as
// `particles render --style FILE` merges and checks the file, with the file's messages.

#include <string>

#include <particles/style.hpp>

namespace particles::api {

// One line of YAML flow: every string double-quoted with escapes (so that "#4682b4", "yes" or a
// label with `: ` stay strings), every number in the shortest text that reads back as the same
// double, only the fields given. An empty Style is "{}". ArgumentError for a RangeScale outside its
// enum (cast in from a number), naming the field.
std::string styleYaml(const Style& style);

// Whether a Style gives nothing: merged, it would change no scenario.
bool isEmpty(const Style& style);

}  // namespace particles::api
