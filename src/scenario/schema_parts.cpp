#include "scenario/schema_parts.hpp"

#include <algorithm>

namespace particles::scenario::schema_parts {

namespace {

constexpr const char* kReferenceForms = "a reference: a name, grid[row][col], body@[x, y] or #index";
constexpr const char* kNamePattern = "^[A-Za-z_][A-Za-z0-9_-]*$";  // references.cpp's isNameStart/isNameChar

}  // namespace

Json number(std::optional<Bound> min, std::optional<Bound> max) {
  Json j = {{"type", "number"}};
  if (min) j[min->inclusive ? "minimum" : "exclusiveMinimum"] = min->value;
  if (max) j[max->inclusive ? "maximum" : "exclusiveMaximum"] = max->value;
  return j;
}

Json pairOf(const Json& item) {
  return {{"type", "array"}, {"items", item}, {"minItems", 2}, {"maxItems", 2}};
}
Json vec2() {
  return pairOf(number());
}
Json vec2Value(const Vec2& v) {
  return Json::array({v.x(), v.y()});
}
Json wholeNumber(long long lo, long long hi) {
  return {{"type", "integer"}, {"minimum", lo}, {"maximum", hi}};
}
Json text() {
  return {{"type", "string"}, {"minLength", 1}};
}
Json name() {
  return {{"type", "string"}, {"pattern", kNamePattern}, {"description", "a unique name"}};
}
Json reference() {
  return {{"type", "string"}, {"minLength", 1}, {"description", kReferenceForms}};
}
Json referenceOrList() {
  return {{"oneOf", Json::array({reference(), {{"type", "array"}, {"items", reference()}, {"minItems", 1}}})}};
}
Json listOf(const Json& item) {
  return {{"type", "array"}, {"items", item}};
}
Json withDescription(Json j, const std::string& description) {
  if (!description.empty()) j["description"] = description;
  return j;
}
Json withDefault(Json j, Json value) {
  j["default"] = std::move(value);
  return j;
}

Json object(const std::vector<std::pair<std::string, Json>>& properties, const std::vector<std::string>& required) {
  Json props = Json::object();
  for (const auto& [key, schema] : properties) {
    const bool isRequired = std::find(required.begin(), required.end(), key) != required.end();
    if (isRequired) {
      props[key] = schema;
    } else {
      // The description and default belong to the key, said once beside the anyOf.
      Json value = schema;
      Json nullable = Json::object();
      for (const char* k : {"description", "default"}) {
        if (value.contains(k)) {
          nullable[k] = value[k];
          value.erase(k);
        }
      }
      nullable["anyOf"] = Json::array({value, {{"type", "null"}}});
      props[key] = nullable;
    }
  }
  Json j = {{"type", "object"}, {"properties", props}, {"additionalProperties", false}};
  if (!required.empty()) j["required"] = required;
  return j;
}

}  // namespace particles::scenario::schema_parts
