#include "args.hpp"

#include <algorithm>
#include <charconv>
#include <system_error>

namespace mpmstab::cli {

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::optional<std::string> nearest(std::string_view name, const std::vector<std::string>& known) {
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (const auto& k : known) {
    const std::size_t d = edit_distance(name, k);
    if (d < best_distance) {
      best_distance = d;
      best = k;
    }
  }
  return best;
}

Args::Args(const std::vector<std::string_view>& argv, const std::vector<OptionSpec>& known) {
  std::vector<std::string> names;
  for (const auto& o : known)
    names.push_back(o.name);
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string_view arg = argv[i];
    if (!arg.starts_with("--")) {
      positional_.push_back(arg);
      continue;
    }
    std::string_view name = arg.substr(2);
    std::optional<std::string_view> inline_value;
    if (const auto eq = name.find('='); eq != std::string_view::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const auto spec = std::find_if(known.begin(), known.end(),
                                   [&](const OptionSpec& o) { return o.name == name; });
    if (spec == known.end()) {
      std::string message = "unknown option --" + std::string(name);
      if (auto guess = nearest(name, names)) message += " (did you mean --" + *guess + "?)";
      throw UsageError(message);
    }
    if (values_.count(name)) throw UsageError("option --" + std::string(name) + " given twice");
    std::string_view value = "";
    if (spec->takes_value) {
      if (inline_value) {
        value = *inline_value;
      } else if (i + 1 < argv.size()) {
        value = argv[++i];
      } else {
        throw UsageError("option --" + std::string(name) + " needs a value");
      }
    } else if (inline_value) {
      throw UsageError("option --" + std::string(name) + " takes no value");
    }
    values_.emplace(std::string(name), value);
  }
}

std::optional<std::string_view> Args::value(std::string_view name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

double parse_double(std::string_view text, std::string_view option) {
  double v = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (text.empty() || ec == std::errc::invalid_argument || ptr != last) {
    throw UsageError("--" + std::string(option) + ": '" + std::string(text) + "' is not a number");
  }
  if (ec == std::errc::result_out_of_range) {
    throw UsageError("--" + std::string(option) + ": '" + std::string(text) +
                     "' is out of the range of a double");
  }
  return v;
}

std::int64_t parse_int(std::string_view text, std::string_view option) {
  std::int64_t v = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (!text.empty() && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (text.empty() || ec == std::errc::invalid_argument || ptr != last) {
    throw UsageError("--" + std::string(option) + ": '" + std::string(text) +
                     "' is not an integer");
  }
  if (ec == std::errc::result_out_of_range) {
    throw UsageError("--" + std::string(option) + ": '" + std::string(text) + "' is too large");
  }
  return v;
}

}  // namespace mpmstab::cli
