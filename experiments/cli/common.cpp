// What the commands that read specs and write reports share: the number of jobs, loading
// specs, the output folder and the --timing option.
#include <unistd.h>

#include <filesystem>

#include "commands.hpp"
#include "parallel.hpp"

namespace mpmstab::cli {

int default_jobs() {
  return static_cast<int>(available_cpus());
}

std::vector<Spec> load_specs(const std::vector<std::string_view>& paths) {
  if (paths.empty()) throw UsageError("missing <spec.json>");
  std::vector<Spec> specs;
  for (auto path : paths) {
    try {
      specs.push_back(load_spec(std::string(path)));
    } catch (const SpecError& e) {
      throw UsageError(e.what());
    }
  }
  return specs;
}

// The output folder must exist or be creatable, and be writable, before anything runs.
std::filesystem::path output_folder(const Args& args) {
  const std::filesystem::path out(args.value("out").value_or("results"));
  std::error_code ec;
  if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec)) {
    throw UsageError("--out: " + out.string() + " is not a folder");
  }
  // Not made here: the first file written makes it, after every argument and input was checked.
  // What must hold now is that it can be: the folder, or its nearest existing ancestor, is a
  // writable folder.
  std::filesystem::path existing = out;
  while (!existing.empty() && !std::filesystem::exists(existing, ec))
    existing = existing.has_parent_path() && existing.parent_path() != existing
                   ? existing.parent_path()
                   : std::filesystem::path();
  if (existing.empty()) existing = ".";
  if (!std::filesystem::is_directory(existing, ec)) {
    throw UsageError("--out: cannot create " + out.string() + ": " + existing.string() +
                     " is not a folder");
  }
  if (::access(existing.c_str(), W_OK) != 0) {
    throw UsageError("--out: " + (existing == out ? out.string() + " is not writable"
                                                  : "cannot create " + out.string() + ": " +
                                                        existing.string() + " is not writable"));
  }
  return out;
}

void make_output_folder(const std::filesystem::path& out) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out, ec)) {
    throw UsageError("--out: cannot create " + out.string() +
                     (ec ? ": " + ec.message() : std::string()));
  }
}

bool omit_timing(const Args& args) {
  const auto v = args.value("timing");
  if (!v || *v == "keep") return false;
  if (*v == "omit") return true;
  throw UsageError("--timing: unknown value '" + std::string(*v) + "' (expected keep or omit)");
}

SpecsAndFolders specs_and_folders(const std::vector<std::string_view>& pos) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::size_t first_dir = 0;
  while (first_dir < pos.size() && !fs::is_directory(fs::path(pos[first_dir]), ec))
    ++first_dir;
  if (first_dir == 0) throw UsageError(std::string(pos.front()) + ": a folder where a spec goes");
  SpecsAndFolders split;
  split.specs.assign(pos.begin(), pos.begin() + long(first_dir));
  for (std::size_t i = first_dir; i < pos.size(); ++i) {
    if (!fs::is_directory(fs::path(pos[i]), ec))
      throw UsageError(std::string(pos[i]) + ": not a folder");
    split.folders.emplace_back(pos[i]);
  }
  if (split.folders.empty()) throw UsageError(std::string(pos.back()) + ": not a folder");
  return split;
}

}  // namespace mpmstab::cli
