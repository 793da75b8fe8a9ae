#include "args.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>
#include <utility>

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

namespace {

// The option a CLI11 parse error is about: its message starts with "--name:" or "name was".
std::string option_of(const CLI::ParseError& e) {
  std::string_view m = e.what();
  if (m.starts_with("--")) m.remove_prefix(2);
  return std::string(m.substr(0, m.find_first_of(": ")));
}

// CLI11's refusals in this program's words, each naming the option.
UsageError usage_error(const CLI::ParseError& e) {
  const std::string what = e.what(), name = "--" + option_of(e);
  if (what.find("At Most") != std::string::npos)
    return UsageError("option " + name + " given twice");
  if (what.find("required") != std::string::npos)
    return UsageError("option " + name + " needs a value");
  if (what.find("flag override") != std::string::npos)
    return UsageError("option " + name + " takes no value");
  return UsageError(what);
}

}  // namespace

// CLI11 does the tokenizing ("--name value", "--name=value", a value that starts with '-', "--"
// before positional arguments that start with it); the refusals are this program's: an unknown
// option with the nearest known one, an option given twice, a missing value, a value given to a
// flag.
Args::Args(const std::vector<std::string_view>& argv, const std::vector<OptionSpec>& known) {
  CLI::App app;
  app.set_help_flag();     // every command declares and prints its own --help
  app.allow_extras(true);  // unknown options are refused below, with a suggestion
  std::vector<std::string> names;
  std::vector<std::pair<std::string, CLI::Option*>> options;
  std::map<std::string, std::string, std::less<>> given;
  std::map<std::string, bool, std::less<>> flags;
  for (const auto& o : known) {
    names.push_back(o.name);
    CLI::Option* opt = o.takes_value
                           ? app.add_option("--" + o.name, given[o.name])->expected(1)
                           : app.add_flag("--" + o.name, flags[o.name])->disable_flag_override();
    opt->multi_option_policy(CLI::MultiOptionPolicy::Throw);
    options.emplace_back(o.name, opt);
  }
  std::vector<std::string> positional;
  app.add_option("positional", positional);
  // CLI11 reads "--flag=" as the flag; this program refuses a value given to a flag, even empty.
  for (const std::string_view arg : argv) {
    if (arg == "--") break;
    if (!arg.starts_with("--") || !arg.ends_with("=")) continue;
    const std::string_view name = arg.substr(2, arg.size() - 3);
    if (flags.count(name)) throw UsageError("option --" + std::string(name) + " takes no value");
  }
  std::vector<std::string> reversed(argv.rbegin(), argv.rend());  // CLI11 pops from the back
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw usage_error(e);
  }
  for (const std::string& extra : app.remaining()) {
    if (extra == "--") continue;
    const std::size_t start = extra.find_first_not_of('-');
    const std::string_view name =
        start == std::string::npos ? std::string_view() : std::string_view(extra).substr(start);
    std::string message = "unknown option " + extra;
    if (auto guess = nearest(name, names)) message += " (did you mean --" + *guess + "?)";
    throw UsageError(message);
  }
  for (const auto& [name, opt] : options)
    if (opt->count() > 0) values_.emplace(name, given.count(name) ? given[name] : std::string());
  positional_storage_ = std::move(positional);
  for (const auto& p : positional_storage_)
    positional_.push_back(p);
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
  // No option takes an infinite or undefined value: "inf" and "nan" are refused here, by name,
  // before any command reads a range ("must be > 0" would misname what is wrong).
  if (!std::isfinite(v)) {
    throw UsageError("--" + std::string(option) + ": '" + std::string(text) +
                     "' is not a finite number");
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
