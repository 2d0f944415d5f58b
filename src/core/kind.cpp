#include "core/kind.hpp"

#include <algorithm>

namespace particles {

const ParamSpec* KindSpec::param(std::string_view key) const {
  const auto it = std::find_if(params.begin(), params.end(), [&](const ParamSpec& p) { return p.key == key; });
  return it == params.end() ? nullptr : &*it;
}

const std::vector<KindSection>& kindSections() {
  static const std::vector<KindSection> sections = {
      {"forces", true}, {"constraints", true}, {"colliders", true}, {"mouse", false}};
  return sections;
}

std::vector<const KindSpec*> kindsOf(std::string_view section) {
  std::vector<const KindSpec*> out;
  for (const KindSpec* k : registeredKinds()) {
    if (k->section == section) out.push_back(k);
  }
  return out;
}

const KindSpec* findKind(std::string_view section, std::string_view type) {
  for (const KindSpec* k : registeredKinds()) {
    if (k->section == section && k->type == type) return k;
  }
  return nullptr;
}

}  // namespace particles
