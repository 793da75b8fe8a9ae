// Starting another program without a shell: an argument vector, never a command string, so
// that no text from a spec, a result or the command line can be read as shell syntax.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace mpmstab {

// Runs argv[0] (looked up in PATH) with the arguments argv[1..], standard input from /dev/null
// and standard error discarded, and waits for it. Returns its standard output (at most
// `max_output` bytes kept), or nullopt when it could not be started or did not exit with 0.
std::optional<std::string> run_program(const std::vector<std::string>& argv,
                                       std::size_t max_output = 1 << 20);

// As run_program, but the program's standard output and error go to this process's standard
// error (for a tool whose messages the user should see), and with `environment` ("NAME=value"
// entries) instead of this process's when given. Returns its exit status, or -1 when it could
// not be started or did not exit normally.
int run_program_visible(const std::vector<std::string>& argv,
                        const std::optional<std::vector<std::string>>& environment = {});

}  // namespace mpmstab
