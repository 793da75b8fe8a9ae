// Command-line parsing shared by the subcommands: "--name value" or "--name=value", tokenized
// by CLI11 (Debian's libcli11-dev); the strict conversions and every refusal's wording are ours.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mpmstab::cli {

// Bad input from the user. main() prints it and exits with status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;  // without "--"
  bool takes_value = true;
};

class Args {
 public:
  // Throws UsageError for an unknown option (suggesting the nearest known one), a missing value
  // or an option given twice.
  Args(const std::vector<std::string_view>& argv, const std::vector<OptionSpec>& known);
  Args(const Args&) = delete;  // positional() views its own storage
  Args& operator=(const Args&) = delete;
  Args(Args&&) = default;
  Args& operator=(Args&&) = default;

  std::optional<std::string_view> value(std::string_view name) const;
  bool flag(std::string_view name) const { return value(name).has_value(); }
  const std::vector<std::string_view>& positional() const { return positional_; }

 private:
  std::map<std::string, std::string, std::less<>> values_;
  std::vector<std::string> positional_storage_;
  std::vector<std::string_view> positional_;  // views of positional_storage_
};

// Strict conversions: the whole text must be a number. Errors name the option.
double parse_double(std::string_view text, std::string_view option);
std::int64_t parse_int(std::string_view text, std::string_view option);

// The candidate closest to `name` by edit distance, if it is close enough to be a likely typo.
std::optional<std::string> nearest(std::string_view name, const std::vector<std::string>& known);

}  // namespace mpmstab::cli
