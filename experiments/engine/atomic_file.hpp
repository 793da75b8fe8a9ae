// Write a file so that readers see either the old content or the new one, never a part:
// write a temporary file beside it, flush it, then rename it over the target.
#pragma once

#include <filesystem>
#include <string_view>

namespace mpmstab {

// Throws std::runtime_error naming the path when the file cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace mpmstab
