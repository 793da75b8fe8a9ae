// The checks on a run's parameters, in one place: the command line and the specs both ask them
// before anything runs. They live beside the scenes because several need the scene a run poses
// (its boundaries, its body, its free surface).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/params.hpp"

namespace mpmstab {

// All checks on a RunParams. Empty result: the parameters are valid.
std::vector<ParamIssue> validate(const RunParams& p);

// The check on what was given rather than on the values: a parameter that the rest of `p` does
// not use is refused when given (a dt with a policy that chooses dt itself, a cfl_factor or a
// safety the policy ignores, a flip_fraction without a blend), so that every record holds only
// what the run used. The command line and the specs both ask it, after reading every value.
std::optional<ParamIssue> check_given(const RunParams& p, std::string_view key);
// The keys check_given can refuse.
const std::vector<std::string>& conditional_parameters();

}  // namespace mpmstab
