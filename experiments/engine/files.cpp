#include "files.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace mpmstab {

namespace fs = std::filesystem;

namespace {

std::string errno_text() {
  return std::strerror(errno);
}

std::string mib(std::uintmax_t bytes) {
  return std::to_string(bytes >> 20) + " MiB";
}

// 16 random hex digits from the kernel's generator.
std::string random_hex() {
  unsigned char bytes[8];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("getrandom: " + errno_text());
    }
    got += static_cast<std::size_t>(n);
  }
  char hex[17];
  for (std::size_t i = 0; i < sizeof bytes; ++i)
    std::snprintf(hex + 2 * i, 3, "%02x", bytes[i]);
  return hex;
}

// ".<target name>.<pid>.<random>.tmp": hidden, unique, and tells which process wrote it.
fs::path temporary_beside(const fs::path& target) {
  std::string name(1, '.');  // built step by step: GCC 12 misreads "." + std::string (-Wrestrict)
  name += target.filename().string();
  name += '.';
  name += std::to_string(static_cast<long>(::getpid()));
  name += '.';
  name += random_hex();
  name += ".tmp";
  return target.parent_path() / name;
}

// A fresh temporary beside `target`, opened for writing; sets `tmp` to its path.
// The folder a report set is published into is made when it is locked for the publication (the
// commands make their --out folder once every argument and input was checked); no other write
// makes a folder (a --history file in a folder that does not exist is refused), but for the
// machine's timings, whose writer (store_timing, report.cpp) makes <out>/cache when a fresh
// clone's `make` records its build time before any sweep made it.
void make_folder_of(const fs::path& target) {
  const fs::path parent = target.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec)
    throw std::runtime_error("cannot create the folder " + parent.string() + ": " + ec.message());
}

int open_temporary(const fs::path& target, fs::path& tmp) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    tmp = temporary_beside(target);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) return fd;
    if (errno != EEXIST) break;
  }
  throw std::runtime_error("cannot write " + target.string() +
                           ": creating a temporary file: " + errno_text());
}

// Writes all of `data` to `fd`; on failure closes it, removes `tmp` and throws.
void write_all(int fd, std::string_view data, const fs::path& tmp, const fs::path& target) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = errno_text();
      ::close(fd);
      ::unlink(tmp.c_str());
      throw std::runtime_error("cannot write " + target.string() + ": write: " + reason);
    }
    done += static_cast<std::size_t>(n);
  }
}

// Flushes `fd` to disk (unless `durability` says not) and closes it; on failure removes `tmp`
// and throws.
void finish(int fd, const fs::path& tmp, const fs::path& target,
            Durability durability = Durability::flushed) {
  const bool synced = durability == Durability::checksummed || ::fsync(fd) == 0;
  const std::string reason = errno_text();
  const bool closed = ::close(fd) == 0;
  if (!synced || !closed) {
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + target.string() + ": " +
                             (synced ? "close: " + errno_text() : "fsync: " + reason));
  }
}

// Writes `content` to a fresh temporary beside `target` and returns its path.
fs::path write_temporary(const fs::path& target, std::string_view content,
                         Durability durability = Durability::flushed) {
  fs::path tmp;
  const int fd = open_temporary(target, tmp);
  write_all(fd, content, tmp, target);
  finish(fd, tmp, target, durability);
  return tmp;
}

void rename_over(const fs::path& from, const fs::path& target) {
  if (::rename(from.c_str(), target.c_str()) != 0) {
    const std::string reason = errno_text();
    ::unlink(from.c_str());
    throw std::runtime_error("cannot write " + target.string() + ": rename: " + reason);
  }
}

// The pid in a name made by temporary_beside or StagingFolder, or -1.
long writer_pid(const std::string& name) {
  std::string stem;
  if (name.size() > 4 && name.ends_with(".tmp")) {
    stem = name.substr(0, name.size() - 4);
  } else if (name.size() > 8 && name.ends_with(".staging")) {
    stem = name.substr(0, name.size() - 8);
  } else {
    return -1;
  }
  const auto random_dot = stem.rfind('.');
  if (random_dot == std::string::npos || stem.size() - random_dot != 17) return -1;
  const auto pid_dot = stem.rfind('.', random_dot - 1);
  if (pid_dot == std::string::npos || pid_dot + 1 >= random_dot) return -1;
  const std::string pid = stem.substr(pid_dot + 1, random_dot - pid_dot - 1);
  if (pid.size() > 9 || !std::all_of(pid.begin(), pid.end(), ::isdigit)) return -1;
  return std::stol(pid);
}

thread_local ReportBatch* t_active = nullptr;

}  // namespace

namespace {

// Opens `path` for reading when it is a regular file of at most `max_bytes`, and gives its size;
// -1 when it does not exist. Throws InputError otherwise, without reading a byte.
int open_input(const fs::path& path, std::uintmax_t max_bytes, std::uintmax_t& size) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return -1;
    throw InputError(path, "cannot be read: " + errno_text());
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const std::string reason = errno_text();
    ::close(fd);
    throw InputError(path, "cannot be read: " + reason);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    throw InputError(path, S_ISDIR(st.st_mode) ? "is a directory, not a file"
                                               : "is not a regular file (a FIFO, a device or a "
                                                 "socket is never read)");
  }
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes) {
    ::close(fd);
    throw InputError(path, "is larger than the limit of " + mib(max_bytes) + " for an input");
  }
  size = static_cast<std::uintmax_t>(st.st_size);
  return fd;
}

}  // namespace

bool input_exists(const fs::path& path, std::uintmax_t max_bytes) {
  std::uintmax_t size = 0;
  const int fd = open_input(path, max_bytes, size);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

std::optional<std::string> read_if_present(const fs::path& path, std::uintmax_t max_bytes) {
  std::uintmax_t size = 0;
  const int fd = open_input(path, max_bytes, size);
  if (fd < 0) return std::nullopt;
  std::string text;
  text.resize(static_cast<std::size_t>(size));
  std::size_t done = 0;
  for (;;) {
    if (done == text.size()) {
      if (text.size() > max_bytes) break;
      text.resize(std::max<std::size_t>(text.size() * 2, 4096));  // the file grew meanwhile
    }
    const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = errno_text();
      ::close(fd);
      throw InputError(path, "cannot be read: " + reason);
    }
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (done > max_bytes) {
    throw InputError(path, "is larger than the limit of " + mib(max_bytes) + " for an input");
  }
  text.resize(done);
  return text;
}

std::string read_input(const fs::path& path, std::uintmax_t max_bytes) {
  auto text = read_if_present(path, max_bytes);
  if (!text) throw InputError(path, "does not exist");
  return std::move(*text);
}

void require_regular_or_absent(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    throw InputError(path, "cannot be inspected: " + errno_text());
  }
  if (S_ISREG(st.st_mode)) return;
  const char* what = S_ISLNK(st.st_mode)                          ? "a symbolic link"
                     : S_ISDIR(st.st_mode)                        ? "a directory"
                     : S_ISFIFO(st.st_mode)                       ? "a FIFO"
                     : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                  : "not a regular file";
  throw InputError(path, std::string("exists and is ") + what +
                             "; the program writes only over regular files (remove it first)");
}

void write_file_atomically(const fs::path& path, std::string_view content, Durability durability) {
  require_regular_or_absent(path);
  rename_over(write_temporary(path, content, durability), path);
}

FileWriter::FileWriter(const fs::path& target) : target_(target) {
  require_regular_or_absent(target_);
  fd_ = open_temporary(target_, temporary_);
}

FileWriter::~FileWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(temporary_.c_str());
  }
}

void FileWriter::flush() {
  const int fd = fd_;
  fd_ = -1;  // write_all closes it on failure
  write_all(fd, buffer_, temporary_, target_);
  fd_ = fd;
  buffer_.clear();
}

void FileWriter::write(std::string_view text) {
  if (fd_ < 0) throw std::logic_error("FileWriter: write after commit");
  buffer_ += text;
  if (buffer_.size() >= (std::size_t{1} << 20)) flush();
}

void FileWriter::commit() {
  if (fd_ < 0) throw std::logic_error("FileWriter: commit twice");
  flush();
  const int fd = fd_;
  fd_ = -1;
  finish(fd, temporary_, target_);
  try {
    require_regular_or_absent(target_);  // planted while the run ran?
  } catch (...) {
    ::unlink(temporary_.c_str());
    throw;
  }
  rename_over(temporary_, target_);
}

void write_if_changed(const fs::path& path, const std::string& content) {
  if (ReportBatch* batch = ReportBatch::active()) {
    batch->add(path, content);
    return;
  }
  require_regular_or_absent(path);
  if (read_if_present(path) == content) return;
  write_file_atomically(path, content);
}

StagingFolder::StagingFolder(const fs::path& parent) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    std::string name(1, '.');
    name += std::to_string(static_cast<long>(::getpid()));
    name += '.';
    name += random_hex();
    name += ".staging";
    path_ = parent / name;
    if (::mkdir(path_.c_str(), 0700) == 0) return;
    if (errno != EEXIST) break;
  }
  throw std::runtime_error("cannot create a staging folder in " + parent.string() + ": " +
                           errno_text());
}

StagingFolder::~StagingFolder() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

FolderLock::FolderLock(const fs::path& folder) {
  const fs::path file = folder / ".mpmstab.lock";
  make_folder_of(file);
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd_ < 0) throw InputError(file, "cannot be opened as a lock file: " + errno_text());
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw InputError(file, "is not a regular file; cannot lock " + folder.string());
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  if (errno != EWOULDBLOCK) {
    const std::string reason = errno_text();
    ::close(fd_);
    throw InputError(file, "cannot be locked: " + reason);
  }
  std::cerr << "waiting for " << file.string() << ": another mpmstab is writing its reports to "
            << folder.string() << "\n";
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const std::string reason = errno_text();
    ::close(fd_);
    throw InputError(file, "cannot be locked: " + reason);
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

// Fault injection for the tests of whole report sets (tests/test_report_sets.cpp): with
// MPMSTAB_TEST_KILL_AFTER_RENAMES=n in the environment, the process kills itself (SIGKILL, as a
// user or the kernel would) right after the n-th rename of a publication.
static void kill_for_test_after_rename(std::size_t renamed) {
  static const long after = [] {
    const char* v = std::getenv("MPMSTAB_TEST_KILL_AFTER_RENAMES");
    return v ? std::atol(v) : 0L;
  }();
  if (after > 0 && renamed == static_cast<std::size_t>(after)) ::kill(::getpid(), SIGKILL);
}

std::size_t remove_stale_temporaries(const fs::path& folder) {
  std::size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] != '.') continue;
    const long pid = writer_pid(name);
    if (pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // still running
    std::error_code rm;
    if (fs::remove_all(it->path(), rm) > 0 && !rm) ++removed;
  }
  return removed;
}

ReportBatch::ReportBatch() {
  if (t_active) throw std::logic_error("report batches do not nest");
  t_active = this;
}

ReportBatch::~ReportBatch() {
  if (t_active == this) t_active = nullptr;
}

ReportBatch* ReportBatch::active() {
  return t_active;
}

void ReportBatch::add(const fs::path& path, std::string content) {
  for (auto& [p, c] : files_) {
    if (p == path) {
      c = std::move(content);  // the last version of a file written twice wins
      return;
    }
  }
  files_.emplace_back(path, std::move(content));
}

namespace {

constexpr std::string_view kJournalSuffix = ".journal";

// A journal entry's temporary must be one temporary_beside made for its target, in the same
// folder: a planted journal can move nothing else.
bool journal_pair_ok(const std::string& temporary, const std::string& target) {
  const auto plain = [](const std::string& n) {
    return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos;
  };
  return plain(temporary) && plain(target) && temporary.rfind("." + target + ".", 0) == 0 &&
         temporary.ends_with(".tmp") && writer_pid(temporary) > 0;
}

// The journal of a publication into `folder`: one line "<temporary>\t<target>" per file, written
// (flushed, renamed into place) before the first rename and removed after the last.
fs::path write_journal(const fs::path& folder,
                       const std::vector<std::pair<fs::path, fs::path>>& renames) {
  std::string text;
  for (const auto& [temporary, target] : renames)
    text += temporary.filename().string() + "\t" + target.filename().string() + "\n";
  std::string name(".publish.");
  name += std::to_string(static_cast<long>(::getpid()));
  name += '.';
  name += random_hex();
  name += kJournalSuffix;
  const fs::path journal = folder / name;
  rename_over(write_temporary(journal, text), journal);
  return journal;
}

}  // namespace

std::size_t finish_interrupted_publications(const fs::path& folder) {
  std::size_t finished = 0;
  std::error_code ec;
  std::vector<fs::path> journals;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(".publish.", 0) == 0 && name.ends_with(kJournalSuffix) && it->is_regular_file())
      journals.push_back(it->path());
  }
  for (const auto& journal : journals) {
    std::istringstream lines(read_if_present(journal).value_or(""));
    for (std::string line; std::getline(lines, line);) {
      const auto tab = line.find('\t');
      if (tab == std::string::npos) continue;
      const std::string temporary = line.substr(0, tab), target = line.substr(tab + 1);
      if (!journal_pair_ok(temporary, target)) continue;
      const fs::path from = folder / temporary, to = folder / target;
      if (!fs::is_regular_file(fs::symlink_status(from, ec))) continue;  // renamed already
      require_regular_or_absent(to);
      rename_over(from, to);
      ++finished;
    }
    fs::remove(journal, ec);
  }
  return finished;
}

std::size_t finish_publications_in(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return 0;
  FolderLock lock(folder);
  return finish_interrupted_publications(folder);
}

std::size_t ReportBatch::publish() {
  t_active = nullptr;
  std::set<fs::path> folders;
  for (const auto& [path, content] : files_)
    folders.insert(path.parent_path());
  std::vector<std::unique_ptr<FolderLock>> locks;  // in sorted order: no two publishers deadlock
  for (const auto& folder : folders) {
    locks.push_back(std::make_unique<FolderLock>(folder));
    finish_interrupted_publications(folder);
    remove_stale_temporaries(folder);
  }
  // 1. Every target must be writable over and is compared before anything is written.
  std::vector<std::size_t> changed;
  for (std::size_t i = 0; i < files_.size(); ++i) {
    require_regular_or_absent(files_[i].first);
    if (read_if_present(files_[i].first) != files_[i].second) changed.push_back(i);
  }
  // 2. All temporaries, then 3. all renames: a failure before the renames leaves every file as
  // it was.
  std::vector<fs::path> temporaries;
  try {
    for (const std::size_t i : changed)
      temporaries.push_back(write_temporary(files_[i].first, files_[i].second));
  } catch (...) {
    for (const auto& t : temporaries)
      ::unlink(t.c_str());
    throw;
  }
  // 3. A journal in each folder names every rename to come, so that a publication killed between
  // two renames is finished by the next process to lock the folder (never left half old, half
  // new); then the renames; then the journals go.
  std::map<fs::path, std::vector<std::pair<fs::path, fs::path>>> by_folder;
  for (std::size_t k = 0; k < changed.size(); ++k)
    by_folder[files_[changed[k]].first.parent_path()].emplace_back(temporaries[k],
                                                                   files_[changed[k]].first);
  std::vector<fs::path> journals;
  if (changed.size() > 1) {
    for (const auto& [folder, renames] : by_folder)
      journals.push_back(write_journal(folder, renames));
  }
  for (std::size_t k = 0; k < changed.size(); ++k) {
    try {
      rename_over(temporaries[k], files_[changed[k]].first);
    } catch (...) {
      for (std::size_t j = k + 1; j < temporaries.size(); ++j)
        ::unlink(temporaries[j].c_str());
      for (const auto& journal : journals)
        ::unlink(journal.c_str());
      throw;
    }
    kill_for_test_after_rename(k + 1);
  }
  for (const auto& journal : journals)
    ::unlink(journal.c_str());
  files_.clear();
  return changed.size();
}

}  // namespace mpmstab
