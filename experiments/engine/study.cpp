#include "study.hpp"

#include <stdexcept>

namespace mpmstab {

namespace {

// Function-local, so that registrations from any translation unit find it constructed.
std::map<std::string, Study, std::less<>>& registry() {
  static std::map<std::string, Study, std::less<>> studies;
  return studies;
}

}  // namespace

const Study* find_study(std::string_view name) {
  const auto& studies = registry();
  const auto it = studies.find(name);
  return it == studies.end() ? nullptr : &it->second;
}

std::vector<const Study*> all_studies() {
  std::vector<const Study*> list;
  for (const auto& [name, study] : registry())
    list.push_back(&study);
  return list;
}

StudyRegistration::StudyRegistration(Study study) {
  const std::string name = study.name;
  if (!registry().emplace(name, std::move(study)).second) {
    throw std::logic_error("study '" + name + "' is registered twice");
  }
}

}  // namespace mpmstab
