// The one way files are written, so that no command ever loses the user's data:
//  - an OutputGuard, owned by the program and handed to the writers, holds what the
//    running command read (NoteInput: device and inode), so that an output that is one
//    of them (the same file by any path, hard links included) is refused before anything
//    is written (an input since deleted, whose inode a new file may reuse, no longer
//    counts); reading a file has no side effect: each face notes its inputs itself, by
//    one rule (a data set's manifest and every sample's files, those set aside included:
//    NoteInputs; the colour tables: NoteFolder; a model or n,k file read: NoteInput), the
//    program for the life of a command, the Python package for each call that writes;
//  - the guard also holds the temporaries in flight, so that the program's signal
//    handlers can remove them (RemoveTemporaries is async-signal-safe: fixed slots,
//    unlink only); the library installs no handler and keeps no process state;
//  - an existing output that is not a regular file (a symlink, a device such as
//    /dev/null, a FIFO, a folder) is refused, never replaced nor written through, with
//    or without a guard;
//  - each file is written to a temporary in its own folder, flushed, then renamed over
//    the old one; a set of files (a report's JSON and HTML, an export's files) is written
//    as a set: every temporary first, then the renames, so a failure while writing leaves
//    the old set whole (the renames hold an flock on the folder, so two commands writing
//    sets into one folder do not mix them);
//  - a temporary's name is the output's name plus ".~PID" (the output's name cut short
//    when the two would pass NAME_MAX, 255 bytes), so any valid output name works;
//  - a write that fails (EFBIG past `ulimit -f`, ENOSPC, EDQUOT, EIO, EPIPE) removes the
//    temporary and throws one Error naming the output and the cause;
//  - an output too large to hold (a sweep's millions of rows) is streamed through
//    StreamOutput: to the same kind of temporary, renamed (or copied to standard output)
//    only once complete.
// Errors are alloycolor::Error naming the output path.
#ifndef ALLOYCOLOR_CORE_OUTPUT_H_
#define ALLOYCOLOR_CORE_OUTPUT_H_

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace alloycolor {

struct Dataset;  // core/dataset.h

// One output file: its path and its whole contents.
struct OutputFile {
  std::string path;
  std::string contents;
};

// What one command read and what it is writing: the inputs no output may replace, and
// the temporaries a signal handler must remove. Owned by the program (one per process or
// per command) and handed to the writers; thread-safe.
class OutputGuard {
 public:
  // The most temporaries tracked at once, and the longest path tracked (longer ones are
  // written, but not removed on a signal).
  static constexpr int kSlots = 64;
  static constexpr std::size_t kSlotBytes = 4096;

  OutputGuard();
  ~OutputGuard();
  OutputGuard(const OutputGuard&) = delete;
  OutputGuard& operator=(const OutputGuard&) = delete;

  // Notes that the command reads `path`; a path that does not exist is ignored.
  void NoteInput(const std::string& path);
  // Notes the files a data set was read from: its manifest and every sample's n,k file (n
  // and k files of a pair), the samples it sets aside included.
  void NoteInputs(const Dataset& dataset);
  // Notes every regular file in `folder` (the colour tables a colorimeter reads:
  // DATA_ROOT/cie); a folder that does not exist is ignored.
  void NoteFolder(const std::string& folder);
  // Throws Error when `path` (already lstat'ed as `info`'s device and inode) is a noted
  // input that is still that file.
  void CheckNotInput(const std::string& path, unsigned long long device, unsigned long long inode);

  // Tracks a temporary being written; returns its slot, or -1 when untracked.
  int TrackTemporary(const std::string& temp) noexcept;
  void ReleaseTemporary(int slot) noexcept;
  // Unlinks every tracked temporary. Async-signal-safe: call it from a signal handler.
  void RemoveTemporaries() const noexcept;

 private:
  struct Slot;
  struct Inputs;
  std::unique_ptr<Slot[]> slots_;
  std::unique_ptr<Inputs> inputs_;
};

// Throws Error when `path` exists and is not a regular file, or (with a guard) names one
// of the guard's inputs.
void CheckOutputPath(const std::string& path, OutputGuard* guard);

// Writes the files as a set (temporaries first, then renames); throws Error naming the
// file at fault, leaving every old file as it was when any temporary fails. With a guard,
// inputs are refused and the temporaries are tracked for its signal handlers.
void WriteFileSetAtomic(const std::vector<OutputFile>& files, OutputGuard* guard = nullptr);

// The temporary a file is written through: same folder, name within NAME_MAX.
std::string TemporaryPathFor(const std::string& path);

// The reason a write failed, in words that tell the user what to do about it (EFBIG:
// the size limit for files, `ulimit -f`; ENOSPC: the file system is full; ...).
std::string WriteErrorText(int error_number);

// Throws Error naming the output when `bytes` more bytes cannot fit: past the size limit
// for files (RLIMIT_FSIZE, `ulimit -f`) or the free space of the file system that holds
// it (statvfs). `path` empty or "-" is standard output, checked when it is a regular
// file (a pipe or terminal has no such limit; what StreamOutput holds past its memory
// goes to $TMPDIR, which is checked instead).
void CheckOutputRoom(const std::string& path, unsigned long long bytes);

// Writes `text` to standard output whole or not at all: CheckOutputRoom first, then every
// byte; throws Error "cannot write standard output: ..." (EPIPE included).
void WriteStandardOutput(const std::string& text);

// "70 GB", "12 MB", "512 bytes": a size for messages (decimal units).
std::string ByteSizeText(unsigned long long bytes);

// One output written as a stream, all or nothing, in bounded memory: a file (`path`), or
// standard output (`path` empty or "-"). The text goes to a temporary — for a file, the
// temporary beside it that WriteFileSetAtomic would use (checked as CheckOutputPath
// first, tracked by the guard for its signal handlers); for standard output, memory up to
// `memory_bytes`, then an unlinked file in $TMPDIR (or /tmp) — and only Commit() makes it appear:
// the temporary is renamed over the file, or copied to standard output. Destroyed without Commit()
// (an error half-way), it leaves nothing: no partial file, not a byte on standard output. Errors
// are alloycolor::Error naming the output ("standard output" for stdout).
class StreamOutput {
 public:
  static constexpr std::size_t kDefaultMemoryBytes = std::size_t{64} << 20;
  explicit StreamOutput(const std::string& path, OutputGuard* guard = nullptr,
                        std::size_t memory_bytes = kDefaultMemoryBytes);
  ~StreamOutput();
  StreamOutput(const StreamOutput&) = delete;
  StreamOutput& operator=(const StreamOutput&) = delete;

  void Write(const char* data, std::size_t size);
  void Write(const std::string& text) { Write(text.data(), text.size()); }
  // Makes the output appear; once only.
  void Commit();
  // The name errors use: the path, or "standard output".
  const std::string& name() const { return name_; }

 private:
  void WriteToFd(const char* data, std::size_t size);
  void SpillToTemporary();

  std::string path_;  // empty for standard output
  std::string name_;
  std::string temp_;  // the named temporary of a file output
  int fd_ = -1;       // the temporary's descriptor, once there is one
  OutputGuard* guard_;
  int slot_ = -1;  // the guard's slot for temp_
  std::size_t memory_bytes_;
  std::string memory_;  // standard output: held here until past memory_bytes
  bool committed_ = false;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_OUTPUT_H_
