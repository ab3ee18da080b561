#include "alloycolor/core/output.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/text.h"

namespace alloycolor {
namespace {

constexpr std::size_t kNameMax = 255;

std::string ErrnoText(int error) { return std::generic_category().message(error); }

// Inputs by (device, inode), with the path they were read by.
using FileId = std::pair<unsigned long long, unsigned long long>;

}  // namespace

// A temporary being written: state 0 free, 1 being filled in, 2 tracked.
struct OutputGuard::Slot {
  std::atomic<int> state{0};
  char path[kSlotBytes];
};

struct OutputGuard::Inputs {
  std::mutex mutex;
  std::map<FileId, std::string> by_id;
};

OutputGuard::OutputGuard()
    : slots_(std::make_unique<Slot[]>(kSlots)), inputs_(std::make_unique<Inputs>()) {
  static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slots");
}

OutputGuard::~OutputGuard() = default;

void OutputGuard::NoteInput(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0) return;
  std::lock_guard<std::mutex> lock(inputs_->mutex);
  inputs_->by_id.emplace(FileId{info.st_dev, info.st_ino}, path);
}

void OutputGuard::NoteInputs(const Dataset& dataset) {
  NoteInput(dataset.manifest_path);
  for (const std::vector<Sample>* samples : {&dataset.samples, &dataset.excluded}) {
    for (const Sample& sample : *samples) {
      NoteInput(sample.path);
      if (!sample.k_path.empty()) NoteInput(sample.k_path);
    }
  }
}

void OutputGuard::NoteFolder(const std::string& folder) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it->is_regular_file(ec)) NoteInput(it->path().string());
  }
}

void OutputGuard::CheckNotInput(const std::string& path, unsigned long long device,
                                unsigned long long inode) {
  std::lock_guard<std::mutex> lock(inputs_->mutex);
  const auto input = inputs_->by_id.find(FileId{device, inode});
  if (input == inputs_->by_id.end()) return;
  // The input is still that file (not deleted, its inode reused by this one)?
  struct stat again;
  if (stat(input->second.c_str(), &again) != 0 || again.st_dev != device || again.st_ino != inode) {
    inputs_->by_id.erase(input);
    return;
  }
  Fail("cannot write '" + path + "': it is one of this command's inputs ('" + input->second +
       "'); choose another output name");
}

int OutputGuard::TrackTemporary(const std::string& temp) noexcept {
  if (temp.size() >= kSlotBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!slots_[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slots_[i].path, temp.c_str(), temp.size() + 1);
    slots_[i].state.store(2);  // the path before the flag
    return i;
  }
  return -1;
}

void OutputGuard::ReleaseTemporary(int slot) noexcept {
  if (slot >= 0 && slot < kSlots) slots_[slot].state.store(0);
}

void OutputGuard::RemoveTemporaries() const noexcept {
  for (int i = 0; i < kSlots; ++i) {
    if (slots_[i].state.load() == 2) unlink(slots_[i].path);
  }
}

std::string WriteErrorText(int error) {
  switch (error) {
    case EFBIG:
      return "the file grew past the largest file allowed (the size limit for files, "
             "'ulimit -f', or the file system's)";
    case ENOSPC:
      return "no space left on the file system";
    case EDQUOT:
      return "the disk quota is exhausted";
    case EIO:
      return "input/output error (the disk or network file system failed)";
    case EPIPE:
      return "the reader closed the pipe";
    default:
      return ErrnoText(error);
  }
}

namespace {

// One temporary being written; removed on destruction unless committed.
struct Temporary {
  std::string path;
  std::string temp;
  OutputGuard* guard = nullptr;
  int slot = -1;
  bool renamed = false;
  ~Temporary() {
    if (!temp.empty() && !renamed) unlink(temp.c_str());
    if (guard) guard->ReleaseTemporary(slot);
  }
};

void WriteTemporary(const OutputFile& file, OutputGuard* guard, Temporary* out) {
  const std::string cannot = "cannot write '" + file.path + "': ";
  out->path = file.path;
  const std::string temp = TemporaryPathFor(file.path);
  out->guard = guard;
  if (guard) out->slot = guard->TrackTemporary(temp);
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  int fd = open(temp.c_str(), flags, 0666);
  if (fd < 0 && errno == EEXIST) {
    // Left by a killed process that had this id: ours to replace.
    unlink(temp.c_str());
    fd = open(temp.c_str(), flags, 0666);
  }
  if (fd < 0) Fail(cannot + WriteErrorText(errno));
  out->temp = temp;
  const auto fail = [&](int error) {
    close(fd);
    Fail(cannot + WriteErrorText(error));
  };
  // A replaced file keeps its permissions.
  struct stat old_info;
  if (stat(file.path.c_str(), &old_info) == 0 && S_ISREG(old_info.st_mode)) {
    fchmod(fd, old_info.st_mode & 07777);
  }
  std::size_t written = 0;
  while (written < file.contents.size()) {
    const ssize_t put = write(fd, file.contents.data() + written, file.contents.size() - written);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) fail(errno);
    written += static_cast<std::size_t>(put);
  }
  if (fsync(fd) != 0) fail(errno);
  if (close(fd) != 0) Fail(cannot + WriteErrorText(errno));
}

void SyncFolder(const std::string& path) {
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const int dir_fd =
      open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    fsync(dir_fd);
    close(dir_fd);
  }
}

}  // namespace

void CheckOutputPath(const std::string& path, OutputGuard* guard) {
  if (path.empty()) Fail("output: empty file name");
  if (path.find('\0') != std::string::npos) Fail("output: the file name holds a NUL byte");
  struct stat info;
  if (lstat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) return;
    Fail("cannot write '" + path + "': " + ErrnoText(errno));
  }
  if (S_ISLNK(info.st_mode)) {
    Fail("cannot write '" + path +
         "': it is a symbolic link; refusing to replace it (give the file it points to, "
         "or another name)");
  }
  if (S_ISDIR(info.st_mode)) Fail("cannot write '" + path + "': it is a folder");
  if (!S_ISREG(info.st_mode)) {
    Fail("cannot write '" + path +
         "': it is a device, FIFO or socket, not a regular file; refusing to replace it");
  }
  if (guard) guard->CheckNotInput(path, info.st_dev, info.st_ino);
}

std::string TemporaryPathFor(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string suffix = ".~" + std::to_string(getpid());
  std::string name = p.filename().string();
  if (name.size() + suffix.size() > kNameMax) name.resize(kNameMax - suffix.size());
  return (p.parent_path() / (name + suffix)).string();
}

void WriteFileSetAtomic(const std::vector<OutputFile>& files, OutputGuard* guard) {
  for (const OutputFile& file : files) CheckOutputPath(file.path, guard);
  for (std::size_t i = 0; i < files.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (std::filesystem::weakly_canonical(files[i].path) ==
          std::filesystem::weakly_canonical(files[j].path)) {
        Fail("cannot write '" + files[i].path + "': the same file is given for two outputs");
      }
    }
  }
  std::vector<Temporary> temporaries(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) WriteTemporary(files[i], guard, &temporaries[i]);
  // Two commands writing a set into one folder must not interleave their renames.
  int lock_fd = -1;
  if (files.size() > 1) {
    const std::string folder = std::filesystem::path(files.front().path).parent_path().string();
    lock_fd = open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (lock_fd >= 0) flock(lock_fd, LOCK_EX);
  }
  struct Unlock {
    int fd;
    ~Unlock() {
      if (fd >= 0) close(fd);  // closing releases the lock
    }
  } unlock{lock_fd};
  for (Temporary& t : temporaries) {
    if (rename(t.temp.c_str(), t.path.c_str()) != 0) {
      Fail("cannot write '" + t.path + "': " + WriteErrorText(errno));
    }
    t.renamed = true;
  }
  // Make the renames durable; a failure here leaves complete files, so it is ignored.
  for (const Temporary& t : temporaries) SyncFolder(t.path);
}

void WriteFileAtomic(const std::string& path, const std::string& contents, OutputGuard* guard) {
  WriteFileSetAtomic({OutputFile{path, contents}}, guard);
}

namespace {

// Writes all of `size` bytes to fd; returns errno, or 0.
int WriteAll(int fd, const char* data, std::size_t size) {
  std::size_t written = 0;
  while (written < size) {
    const ssize_t put = write(fd, data + written, size - written);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) return errno;
    written += static_cast<std::size_t>(put);
  }
  return 0;
}

}  // namespace

StreamOutput::StreamOutput(const std::string& path, OutputGuard* guard, std::size_t memory_bytes)
    : path_(path == "-" ? std::string() : path),
      name_(path_.empty() ? "standard output" : path_),
      guard_(guard),
      memory_bytes_(memory_bytes) {
  if (path_.empty()) return;
  CheckOutputPath(path_, guard_);
  temp_ = TemporaryPathFor(path_);
  if (guard_) slot_ = guard_->TrackTemporary(temp_);
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  fd_ = open(temp_.c_str(), flags, 0666);
  if (fd_ < 0 && errno == EEXIST) {  // left by a killed process that had this id
    unlink(temp_.c_str());
    fd_ = open(temp_.c_str(), flags, 0666);
  }
  if (fd_ < 0) {
    const int error = errno;
    if (guard_) guard_->ReleaseTemporary(slot_);
    Fail("cannot write '" + path_ + "': " + WriteErrorText(error));
  }
  struct stat old_info;  // a replaced file keeps its permissions
  if (stat(path_.c_str(), &old_info) == 0 && S_ISREG(old_info.st_mode)) {
    fchmod(fd_, old_info.st_mode & 07777);
  }
}

StreamOutput::~StreamOutput() {
  if (fd_ >= 0) close(fd_);
  if (!committed_ && !temp_.empty()) unlink(temp_.c_str());
  if (guard_) guard_->ReleaseTemporary(slot_);
}

void StreamOutput::WriteToFd(const char* data, std::size_t size) {
  if (const int error = WriteAll(fd_, data, size); error != 0) {
    Fail("cannot write '" +
         (path_.empty() ? std::string("a temporary file for standard output") : path_) +
         "': " + WriteErrorText(error));
  }
}

void StreamOutput::SpillToTemporary() {
  const char* dir = std::getenv("TMPDIR");
  const std::string folder = dir && *dir ? dir : "/tmp";
  // Unlinked at once: nothing is left behind, whatever ends the process.
  fd_ = open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd_ < 0) {
    std::string name = folder + "/alloycolor-stdout-XXXXXX";
    fd_ = mkostemp(name.data(), O_CLOEXEC);
    if (fd_ >= 0) unlink(name.c_str());
  }
  if (fd_ < 0) {
    Fail("cannot hold standard output past " + std::to_string(memory_bytes_ >> 20) +
         " MiB: no temporary file in '" + folder + "': " + ErrnoText(errno));
  }
  WriteToFd(memory_.data(), memory_.size());
  std::string().swap(memory_);
}

void StreamOutput::Write(const char* data, std::size_t size) {
  if (committed_) Fail("cannot write '" + name_ + "': already complete");
  if (path_.empty() && fd_ < 0) {
    if (memory_.size() + size <= memory_bytes_) {
      memory_.append(data, size);
      return;
    }
    SpillToTemporary();
  }
  WriteToFd(data, size);
}

void StreamOutput::Commit() {
  if (committed_) return;
  if (!path_.empty()) {
    if (fsync(fd_) != 0) Fail("cannot write '" + path_ + "': " + WriteErrorText(errno));
    const int fd = fd_;
    fd_ = -1;
    if (close(fd) != 0) Fail("cannot write '" + path_ + "': " + WriteErrorText(errno));
    CheckOutputPath(path_, guard_);  // still no symlink, device or input put there meanwhile
    if (rename(temp_.c_str(), path_.c_str()) != 0) {
      Fail("cannot write '" + path_ + "': " + WriteErrorText(errno));
    }
    committed_ = true;
    SyncFolder(path_);
    return;
  }
  if (fd_ < 0) {
    WriteStandardOutput(memory_);
    committed_ = true;
    std::string().swap(memory_);
    return;
  }
  const off_t size = lseek(fd_, 0, SEEK_END);
  if (size < 0 || lseek(fd_, 0, SEEK_SET) != 0) {
    Fail("cannot read back standard output: " + ErrnoText(errno));
  }
  CheckOutputRoom("", static_cast<unsigned long long>(size));
  committed_ = true;
  std::vector<char> block(std::size_t{1} << 20);
  for (;;) {
    const ssize_t got = read(fd_, block.data(), block.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) Fail("cannot read back standard output: " + ErrnoText(errno));
    if (got == 0) break;
    if (const int error = WriteAll(STDOUT_FILENO, block.data(), static_cast<std::size_t>(got));
        error != 0) {
      Fail("cannot write standard output: " + WriteErrorText(error));
    }
  }
}

std::string ByteSizeText(unsigned long long bytes) {
  static constexpr const char* kUnits[] = {"kB", "MB", "GB", "TB", "PB", "EB"};
  if (bytes < 1000) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double value = static_cast<double>(bytes);
  int unit = -1;
  while (value >= 1000.0 && unit < 5) {
    value /= 1000.0;
    ++unit;
  }
  char text[32];
  const bool whole = value >= 10.0 || value == static_cast<double>(static_cast<int>(value));
  std::snprintf(text, sizeof text, whole ? "%.0f %s" : "%.1f %s", value, kUnits[unit]);
  return text;
}

namespace {

// Throws when `bytes` more bytes past `offset` exceed the size limit for files.
void CheckFileSizeLimit(const std::string& name, unsigned long long offset,
                        unsigned long long bytes) {
  struct rlimit limit;
  if (getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
  if (offset + bytes > static_cast<unsigned long long>(limit.rlim_cur)) {
    Fail("cannot write " + name + ": " + ByteSizeText(bytes) +
         " to write, past the size limit for files (" +
         ByteSizeText(static_cast<unsigned long long>(limit.rlim_cur)) + ", 'ulimit -f')");
  }
}

void CheckFreeSpace(const std::string& name, const struct statvfs& fs, unsigned long long bytes) {
  if (fs.f_blocks == 0) return;  // a pseudo file system that counts no blocks
  const unsigned long long free_bytes =
      static_cast<unsigned long long>(fs.f_bavail) * static_cast<unsigned long long>(fs.f_frsize);
  if (bytes > free_bytes) {
    Fail("cannot write " + name + ": " + ByteSizeText(bytes) + " to write, " +
         ByteSizeText(free_bytes) + " free on its file system");
  }
}

}  // namespace

void CheckOutputRoom(const std::string& path, unsigned long long bytes) {
  if (path.empty() || path == "-") {
    struct stat info;
    if (fstat(STDOUT_FILENO, &info) != 0) return;
    if (S_ISREG(info.st_mode)) {
      const off_t offset = lseek(STDOUT_FILENO, 0, SEEK_CUR);
      CheckFileSizeLimit("standard output",
                         offset > 0 ? static_cast<unsigned long long>(offset) : 0, bytes);
      struct statvfs fs;
      if (fstatvfs(STDOUT_FILENO, &fs) == 0) CheckFreeSpace("standard output", fs, bytes);
    } else if (bytes > StreamOutput::kDefaultMemoryBytes) {
      const char* dir = std::getenv("TMPDIR");
      const std::string folder = dir && *dir ? dir : "/tmp";
      struct statvfs fs;
      if (statvfs(folder.c_str(), &fs) == 0) {
        CheckFreeSpace("standard output (held in '" + folder + "' until complete)", fs, bytes);
      }
    }
    return;
  }
  const std::string name = "'" + path + "'";
  CheckFileSizeLimit(name, 0, bytes);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  struct statvfs fs;
  if (statvfs(folder.empty() ? "." : folder.c_str(), &fs) == 0) CheckFreeSpace(name, fs, bytes);
}

void WriteStandardOutput(const std::string& text) {
  CheckOutputRoom("", text.size());
  if (const int error = WriteAll(STDOUT_FILENO, text.data(), text.size()); error != 0) {
    Fail("cannot write standard output: " + WriteErrorText(error));
  }
}

}  // namespace alloycolor
