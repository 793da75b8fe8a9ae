// The solver's version. Raise it whenever a change can move a result: cached results and
// blessed references are keyed by it.
#pragma once

namespace mpmstab {
inline constexpr const char* kSolverVersion = "6";
}  // namespace mpmstab
