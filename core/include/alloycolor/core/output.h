// The one way the program writes files, so that no command ever loses the user's data:
//  - every file a command reads through ReadFileText is noted as an input (device and
//    inode), and an output that is one of them (the same file by any path, hard links
//    included) is refused before anything is written (an input since deleted, whose inode
//    a new file may reuse, no longer counts);
//  - an existing output that is not a regular file (a symlink, a device such as
//    /dev/null, a FIFO, a folder) is refused, never replaced nor written through;
//  - each file is written to a temporary in its own folder, flushed, then renamed over
//    the old one; a set of files (a report's JSON and HTML, an export's files) is written
//    as a set: every temporary first, then the renames, so a failure while writing leaves
//    the old set whole (the renames hold an flock on the folder, so two commands writing
//    sets into one folder do not mix them);
//  - a temporary's name is the output's name plus ".~PID" (the output's name cut short
//    when the two would pass NAME_MAX, 255 bytes), so any valid output name works;
//  - an output too large to hold (a sweep's millions of rows) is streamed through
//    StreamOutput: to the same kind of temporary, renamed (or copied to standard output)
//    only once complete;
//  - InstallTemporaryCleanup (called once by the program) makes SIGINT, SIGTERM and
//    SIGHUP unlink the temporaries being written (async-signal-safe: fixed slots, unlink
//    only) before the signal takes its default effect.
// Errors are alloycolor::Error naming the output path.
#ifndef ALLOYCOLOR_CORE_OUTPUT_H_
#define ALLOYCOLOR_CORE_OUTPUT_H_

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace alloycolor {

// One output file: its path and its whole contents.
struct OutputFile {
  std::string path;
  std::string contents;
};

// Notes that the running command read `path` (ReadFileText calls this).
void NoteInputFile(const std::string& path);

// Throws Error when `path` names a noted input, or exists and is not a regular file.
void CheckOutputPath(const std::string& path);

// Writes the files as a set (temporaries first, then renames); throws Error naming the
// file at fault, leaving every old file as it was when any temporary fails.
void WriteFileSetAtomic(const std::vector<OutputFile>& files);

// The temporary a file is written through: same folder, name within NAME_MAX.
std::string TemporaryPathFor(const std::string& path);

// Installs the SIGINT, SIGTERM and SIGHUP handlers that remove temporaries in flight.
void InstallTemporaryCleanup();

// One output written as a stream, all or nothing, in bounded memory: a file (`path`), or
// standard output (`path` empty or "-"). The text goes to a temporary — for a file, the
// temporary beside it that WriteFileSetAtomic would use (checked as CheckOutputPath
// first, removed on a signal); for standard output, memory up to `memory_bytes`, then an
// unlinked file in $TMPDIR (or /tmp) — and only Commit() makes it appear: the temporary
// is renamed over the file, or copied to standard output. Destroyed without Commit() (an
// error half-way), it leaves nothing: no partial file, not a byte on standard output.
// Errors are alloycolor::Error naming the output ("standard output" for stdout).
class StreamOutput {
 public:
  static constexpr std::size_t kDefaultMemoryBytes = std::size_t{64} << 20;
  explicit StreamOutput(const std::string& path, std::size_t memory_bytes = kDefaultMemoryBytes);
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
  int slot_ = -1;     // the signal handler's slot for temp_
  std::size_t memory_bytes_;
  std::string memory_;  // standard output: held here until past memory_bytes
  bool committed_ = false;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_OUTPUT_H_
