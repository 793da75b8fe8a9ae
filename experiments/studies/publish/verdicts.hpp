// The words a report judges a run by, each defined once, from the code's own lists: a run's
// outcome (core/base/result.hpp), the reason an unstable run stopped (core/base/failure.hpp) and
// its accuracy class (core/base/accuracy.hpp). docs/studies.md's tables of them are generated from
// these definitions (mpmstab documents), so a name the code gains appears there, and a table
// edited by hand fails `make check`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/accuracy.hpp"
#include "base/failure.hpp"
#include "base/result.hpp"

namespace mpmstab {

// What each value means, in one sentence with its thresholds printed from the code's constants.
std::string definition(Outcome o);
std::string definition(FailureReason r);
std::string definition(Accuracy a);

// Every value of each list, in the order of its enum.
std::vector<Outcome> all_outcomes();
std::vector<FailureReason> all_failure_reasons();
std::vector<Accuracy> all_accuracy_classes();

// A Markdown table of one list: | name | definition |.
std::string outcomes_table();
std::string failure_reasons_table();
std::string accuracy_classes_table();

}  // namespace mpmstab
