// Every file the program reads or writes goes through this one place.
//
// Reading: only a regular file of bounded size is read; a FIFO, a device or a folder is refused
// without blocking on it. Writing: a temporary file with a random name is created beside the
// target (O_CREAT | O_EXCL | O_NOFOLLOW, so nothing planted at that name is followed), written,
// flushed to disk and renamed over the target; a target that exists and is not a regular file
// (a symbolic link, a FIFO, a device, a folder) is refused. Readers therefore see the old content
// or the new one, never a part, and nothing outside the target's folder is ever written.
//
// A report set is whole or absent: while a ReportBatch is open, write_if_changed only collects
// the files; ReportBatch::publish() then writes every temporary, a journal naming the renames,
// and renames them one after the other under an exclusive lock on the folder, so two sweeps
// never interleave their files; a publication killed between two renames is finished from its
// journal by the next process that locks the folder.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mpmstab {

// An input or an output the program refuses; the command exits with status 2. The message names
// the file.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // "<path>: <detail>"; detail() is the part after the path.
  InputError(const std::filesystem::path& path, std::string detail)
      : std::runtime_error(path.string() + ": " + detail), detail_(std::move(detail)) {}
  const std::string& detail() const { return detail_; }

 private:
  std::string detail_;
};

// The largest input read (spec, reference, results, cache record, benchmark): 64 MiB.
inline constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t{64} << 20;

// The content of a regular file of at most `max_bytes`. Throws InputError naming the path when it
// is absent, not a regular file, too large or unreadable.
std::string read_input(const std::filesystem::path& path,
                       std::uintmax_t max_bytes = kMaxInputBytes);

// Whether `path` exists, with read_input's checks on it (a regular file of at most `max_bytes`,
// else InputError), without reading it: for files another program will read.
bool input_exists(const std::filesystem::path& path, std::uintmax_t max_bytes = kMaxInputBytes);

// As read_input, but an absent file gives std::nullopt.
std::optional<std::string> read_if_present(const std::filesystem::path& path,
                                           std::uintmax_t max_bytes = kMaxInputBytes);

// Throws InputError when `path` exists and is not a regular file (lstat: a symbolic link is not
// one): the program never writes over such a thing.
void require_regular_or_absent(const std::filesystem::path& path);

// Whether a written file is flushed to disk (fsync) before its rename: every report is; a cache
// record is not, since one torn by a crash fails its checksum and is computed again (and an fsync
// per case costs 0.2 ms here, more on a laptop's disk, for each of the thousands of cases).
enum class Durability { flushed, checksummed };

// Writes `content` to `path` through a fresh temporary file and a rename. Throws InputError for a
// refused target, std::runtime_error naming the path when the folder cannot be written.
void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           Durability durability = Durability::flushed);

// A file written piece by piece and published at the end as write_file_atomically publishes it:
// the target is checked at construction and untouched until commit(); destroyed without
// commit(), the temporary is removed. Writes are buffered (1 MiB).
class FileWriter {
 public:
  explicit FileWriter(const std::filesystem::path& target);
  ~FileWriter();
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;
  void write(std::string_view text);
  void commit();

 private:
  void flush();
  std::filesystem::path target_, temporary_;
  int fd_ = -1;
  std::string buffer_;
};

// As write_file_atomically, unless the file already holds exactly `content` (then it is left as
// it is, modification time included). Inside an open ReportBatch the file is only collected.
void write_if_changed(const std::filesystem::path& path, const std::string& content);

// A private folder (mode 0700, random name, removed with everything in it on destruction) inside
// `parent`, for another program's outputs before they are published.
class StagingFolder {
 public:
  explicit StagingFolder(const std::filesystem::path& parent);
  ~StagingFolder();
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// An exclusive lock (flock) on <folder>/.mpmstab.lock, held for the object's lifetime. A second
// holder waits, after saying on stderr whom it waits for.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& folder);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

// Finishes the publications into `folder` that a killed process left between two renames: each
// journal's remaining renames are done and the journal removed, so that every report set there
// is whole again (new). Called under the folder's lock by every publication and by the commands
// that read reports before they read them. Returns how many files it renamed.
std::size_t finish_interrupted_publications(const std::filesystem::path& folder);
// The same under the folder's lock, where the folder exists (for a command about to read it).
std::size_t finish_publications_in(const std::filesystem::path& folder);

// Removes the temporaries and staging folders in `folder` left by a process that no longer runs
// (killed while writing). Returns how many it removed.
std::size_t remove_stale_temporaries(const std::filesystem::path& folder);

// The files of one report set, published together (see above). Batches do not nest; one is open
// per thread at most.
class ReportBatch {
 public:
  ReportBatch();
  ~ReportBatch();  // an unpublished batch writes nothing
  ReportBatch(const ReportBatch&) = delete;
  ReportBatch& operator=(const ReportBatch&) = delete;

  // Writes every collected file whose content changed: all temporaries first, then the renames,
  // under the lock of each folder written to. Returns how many files changed.
  std::size_t publish();

  // The batch open on this thread, if any.
  static ReportBatch* active();
  void add(const std::filesystem::path& path, std::string content);

 private:
  std::vector<std::pair<std::filesystem::path, std::string>> files_;
};

}  // namespace mpmstab
