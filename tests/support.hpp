// Helpers shared by the tests: running the command-line program, and a small quick case.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "base/params.hpp"

namespace mpmstab::test_support {

struct CliOutcome {
  int status;          // exit status; -1 if the program did not exit normally
  std::string output;  // stdout and stderr together
};

// Splits `line` into words as a shell would for plain words and quotes: whitespace separates;
// '...' keeps everything; "..." keeps everything but \" and \\. Nothing else is special: no
// variable, no substitution, no redirection (the program is started without a shell).
inline std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::string w;
  bool in_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) out.push_back(w);
      w.clear();
      in_word = false;
    } else if (c == '\'') {
      in_word = true;
      for (++i; i < line.size() && line[i] != '\''; ++i)
        w += line[i];
    } else if (c == '"') {
      in_word = true;
      for (++i; i < line.size() && line[i] != '"'; ++i) {
        if (line[i] == '\\' && i + 1 < line.size() && (line[i + 1] == '"' || line[i + 1] == '\\'))
          ++i;
        w += line[i];
      }
    } else {
      in_word = true;
      w += c;
    }
  }
  if (in_word) out.push_back(w);
  return out;
}

// Runs `program` with `argv` (argv[0] first; no shell) and collects all it prints on its
// standard output and error. `cwd`: the folder it runs in (empty: this one); `env`: its whole
// environment (none given: this process's).
inline CliOutcome run_program(const char* program, std::vector<std::string> argv,
                              const std::string& cwd = "",
                              std::optional<std::vector<std::string>> env = std::nullopt) {
  int fd[2];
  if (pipe(fd) != 0) return {-1, "pipe failed"};
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    dup2(fd[1], STDOUT_FILENO);
    dup2(fd[1], STDERR_FILENO);
    close(fd[1]);
    if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(126);
    std::vector<char*> v;
    for (auto& a : argv)
      v.push_back(a.data());
    v.push_back(nullptr);
    if (env) {
      std::vector<char*> e;
      for (auto& entry : *env)
        e.push_back(entry.data());
      e.push_back(nullptr);
      execve(program, v.data(), e.data());
    } else {
      execv(program, v.data());
    }
    _exit(127);
  }
  close(fd[1]);
  std::string output;
  std::array<char, 4096> buffer;
  for (ssize_t n; (n = read(fd[0], buffer.data(), buffer.size())) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    output.append(buffer.data(), static_cast<std::size_t>(n));
  }
  close(fd[0]);
  int raw = 0;
  while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {
  }
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, output};
}

// Runs build/mpmstab with the words of `args` (no shell) and collects all it prints on its
// standard output and error.
inline CliOutcome run_mpmstab(const std::string& args) {
  std::vector<std::string> argv = words(args);
  argv.insert(argv.begin(), MPMSTAB_BIN);
  return run_program(MPMSTAB_BIN, std::move(argv));
}

// A GIMP case of the bar that runs in milliseconds: E = 4, A = 0.015, dt = 1e-3, T = 0.2 on
// 20 cells.
inline RunParams quick_case() {
  RunParams p;
  p.method = Method::gimp;
  p.E = 4;
  p.A = 0.015;
  p.dt = 1e-3;
  p.T = 0.2;
  p.cells = 20;
  return p;
}

// The bar at a small amplitude and a small step, so that the spatial error shows: E = 4,
// A = 1e-3, dt = 1e-4, T = 0.5, 2 particles per cell on `cells` cells.
inline RunParams small_amplitude_bar(Method m, int cells) {
  RunParams p;
  p.method = m;
  p.E = 4;
  p.A = 1e-3;
  p.dt = 1e-4;
  p.T = 0.5;
  p.cells = cells;
  p.ppc = 2;
  return p;
}

}  // namespace mpmstab::test_support
