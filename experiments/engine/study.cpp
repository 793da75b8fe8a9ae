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

std::vector<const nlohmann::ordered_json*> follow_ups_of(
    const std::vector<nlohmann::ordered_json>& follow_up, std::size_t of, std::string_view role) {
  std::vector<const nlohmann::ordered_json*> out;
  for (const auto& r : follow_up) {
    const auto o = r.find(kFollowUpOf);
    const auto k = r.find(kFollowUpRole);
    if (o == r.end() || k == r.end() || !k->is_string()) continue;
    const bool same_case = o->is_null() ? of == FollowUp::kNoCase
                                        : o->is_number_integer() && o->get<long long>() >= 0 &&
                                              static_cast<std::size_t>(o->get<long long>()) == of;
    if (same_case && k->get_ref<const std::string&>() == role) out.push_back(&r);
  }
  return out;
}

StudyRegistration::StudyRegistration(Study study) {
  const std::string name = study.name;
  if (!registry().emplace(name, std::move(study)).second) {
    throw std::logic_error("study '" + name + "' is registered twice");
  }
}

}  // namespace mpmstab
