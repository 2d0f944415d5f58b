#pragma once
// The pieces scenarioJsonSchema() (schema.cpp) is written with, and the parts of it written in a
// file of their own: the style section and render.view (style_schema.cpp). Internal to the
// scenario loader.

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/kind.hpp"
#include "core/state.hpp"
#include "scenario/scenario.hpp"

namespace particles::scenario::schema_parts {

// Keys keep the order they are written in, so the schema reads like docs/scenarios.md.
using Json = nlohmann::ordered_json;

Json number(std::optional<Bound> min = {}, std::optional<Bound> max = {});
Json pairOf(const Json& item);
Json vec2();
Json vec2Value(const Vec2& v);
Json wholeNumber(long long lo, long long hi);
Json text();
Json name();
Json reference();
Json referenceOrList();
Json listOf(const Json& item);
Json withDescription(Json j, const std::string& description);
Json withDefault(Json j, Json value);
// A map with exactly these keys; `required` among them. An optional key written without a value
// counts as absent in the loader, so optional keys also accept null.
Json object(const std::vector<std::pair<std::string, Json>>& properties, const std::vector<std::string>& required);

// The `style` section, and render.view (its camera modes, and `defaults`' center and height); the
// definitions they refer to (`#/definitions/NAME`), for the schema's root.
Json styleSchema();
Json styleDefinitions();
Json viewSchema(const RenderSettings& defaults);

}  // namespace particles::scenario::schema_parts
