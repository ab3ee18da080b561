#include "alloycolor/core/output.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/io.h"
#include "alloycolor/core/text.h"

namespace alloycolor {
namespace {

constexpr std::size_t kNameMax = 255;

std::string ErrnoText(int error) { return std::generic_category().message(error); }

// Inputs by (device, inode), with the path they were read by.
using FileId = std::pair<dev_t, ino_t>;

std::mutex& InputsMutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<FileId, std::string>& Inputs() {
  static std::map<FileId, std::string> inputs;
  return inputs;
}

// Temporaries being written, for the signal handler: fixed slots, no allocation there.
constexpr int kSlots = 64;
constexpr std::size_t kSlotBytes = 4096;
char g_slot_path[kSlots][kSlotBytes];
volatile sig_atomic_t g_slot_used[kSlots];
std::mutex g_slot_mutex;

int TakeSlot(const std::string& temp) {
  if (temp.size() >= kSlotBytes) return -1;
  std::lock_guard<std::mutex> lock(g_slot_mutex);
  for (int i = 0; i < kSlots; ++i) {
    if (g_slot_used[i]) continue;
    std::memcpy(g_slot_path[i], temp.c_str(), temp.size() + 1);
    std::atomic_signal_fence(std::memory_order_seq_cst);  // the path before the flag
    g_slot_used[i] = 1;
    return i;
  }
  return -1;
}

void ReleaseSlot(int slot) {
  if (slot < 0) return;
  std::lock_guard<std::mutex> lock(g_slot_mutex);
  g_slot_used[slot] = 0;
}

extern "C" void RemoveTemporariesAndRaise(int signal_number) {
  for (int i = 0; i < kSlots; ++i) {
    if (g_slot_used[i]) unlink(g_slot_path[i]);
  }
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  sigaction(signal_number, &action, nullptr);
  raise(signal_number);
}

// One temporary being written; removed on destruction unless committed.
struct Temporary {
  std::string path;
  std::string temp;
  int slot = -1;
  bool renamed = false;
  ~Temporary() {
    if (!temp.empty() && !renamed) unlink(temp.c_str());
    ReleaseSlot(slot);
  }
};

void WriteTemporary(const OutputFile& file, Temporary* out) {
  const std::string cannot = "cannot write '" + file.path + "': ";
  out->path = file.path;
  const std::string temp = TemporaryPathFor(file.path);
  out->slot = TakeSlot(temp);
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  int fd = open(temp.c_str(), flags, 0666);
  if (fd < 0 && errno == EEXIST) {
    // Left by a killed process that had this id: ours to replace.
    unlink(temp.c_str());
    fd = open(temp.c_str(), flags, 0666);
  }
  if (fd < 0) Fail(cannot + ErrnoText(errno));
  out->temp = temp;
  const auto fail = [&](int error) {
    close(fd);
    Fail(cannot + ErrnoText(error));
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
  if (close(fd) != 0) Fail(cannot + ErrnoText(errno));
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

void NoteInputFile(const std::string& path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0) return;
  std::lock_guard<std::mutex> lock(InputsMutex());
  Inputs().emplace(FileId{info.st_dev, info.st_ino}, path);
}

void CheckOutputPath(const std::string& path) {
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
  std::lock_guard<std::mutex> lock(InputsMutex());
  const auto input = Inputs().find(FileId{info.st_dev, info.st_ino});
  if (input != Inputs().end()) {
    // The input is still that file (not deleted, its inode reused by this one)?
    struct stat again;
    if (stat(input->second.c_str(), &again) != 0 || again.st_dev != info.st_dev ||
        again.st_ino != info.st_ino) {
      Inputs().erase(input);
      return;
    }
    Fail("cannot write '" + path + "': it is one of this command's inputs ('" + input->second +
         "'); choose another output name");
  }
}

std::string TemporaryPathFor(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string suffix = ".~" + std::to_string(getpid());
  std::string name = p.filename().string();
  if (name.size() + suffix.size() > kNameMax) name.resize(kNameMax - suffix.size());
  return (p.parent_path() / (name + suffix)).string();
}

void WriteFileSetAtomic(const std::vector<OutputFile>& files) {
  for (const OutputFile& file : files) CheckOutputPath(file.path);
  for (std::size_t i = 0; i < files.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (std::filesystem::weakly_canonical(files[i].path) ==
          std::filesystem::weakly_canonical(files[j].path)) {
        Fail("cannot write '" + files[i].path + "' twice in one command");
      }
    }
  }
  std::vector<Temporary> temporaries(files.size());
  for (std::size_t i = 0; i < files.size(); ++i) WriteTemporary(files[i], &temporaries[i]);
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
      Fail("cannot write '" + t.path + "': " + ErrnoText(errno));
    }
    t.renamed = true;
  }
  // Make the renames durable; a failure here leaves complete files, so it is ignored.
  for (const Temporary& t : temporaries) SyncFolder(t.path);
}

void WriteFileAtomic(const std::string& path, const std::string& contents) {
  WriteFileSetAtomic({OutputFile{path, contents}});
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

StreamOutput::StreamOutput(const std::string& path, std::size_t memory_bytes)
    : path_(path == "-" ? std::string() : path),
      name_(path_.empty() ? "standard output" : path_),
      memory_bytes_(memory_bytes) {
  if (path_.empty()) return;
  CheckOutputPath(path_);
  temp_ = TemporaryPathFor(path_);
  slot_ = TakeSlot(temp_);
  const int flags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW;
  fd_ = open(temp_.c_str(), flags, 0666);
  if (fd_ < 0 && errno == EEXIST) {  // left by a killed process that had this id
    unlink(temp_.c_str());
    fd_ = open(temp_.c_str(), flags, 0666);
  }
  if (fd_ < 0) {
    const int error = errno;
    ReleaseSlot(slot_);
    Fail("cannot write '" + path_ + "': " + ErrnoText(error));
  }
  struct stat old_info;  // a replaced file keeps its permissions
  if (stat(path_.c_str(), &old_info) == 0 && S_ISREG(old_info.st_mode)) {
    fchmod(fd_, old_info.st_mode & 07777);
  }
}

StreamOutput::~StreamOutput() {
  if (fd_ >= 0) close(fd_);
  if (!committed_ && !temp_.empty()) unlink(temp_.c_str());
  ReleaseSlot(slot_);
}

void StreamOutput::WriteToFd(const char* data, std::size_t size) {
  if (const int error = WriteAll(fd_, data, size); error != 0) {
    Fail("cannot write '" +
         (path_.empty() ? std::string("a temporary file for standard output") : path_) +
         "': " + ErrnoText(error));
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
    if (fsync(fd_) != 0) Fail("cannot write '" + path_ + "': " + ErrnoText(errno));
    const int fd = fd_;
    fd_ = -1;
    if (close(fd) != 0) Fail("cannot write '" + path_ + "': " + ErrnoText(errno));
    CheckOutputPath(path_);  // still no symlink, device or input put there meanwhile
    if (rename(temp_.c_str(), path_.c_str()) != 0) {
      Fail("cannot write '" + path_ + "': " + ErrnoText(errno));
    }
    committed_ = true;
    SyncFolder(path_);
    return;
  }
  committed_ = true;
  if (fd_ < 0) {
    if (const int error = WriteAll(STDOUT_FILENO, memory_.data(), memory_.size()); error != 0) {
      Fail("cannot write standard output: " + ErrnoText(error));
    }
    std::string().swap(memory_);
    return;
  }
  if (lseek(fd_, 0, SEEK_SET) != 0) Fail("cannot read back standard output: " + ErrnoText(errno));
  std::vector<char> block(std::size_t{1} << 20);
  for (;;) {
    const ssize_t got = read(fd_, block.data(), block.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) Fail("cannot read back standard output: " + ErrnoText(errno));
    if (got == 0) break;
    if (const int error = WriteAll(STDOUT_FILENO, block.data(), static_cast<std::size_t>(got));
        error != 0) {
      Fail("cannot write standard output: " + ErrnoText(error));
    }
  }
}

void InstallTemporaryCleanup() {
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = RemoveTemporariesAndRaise;
  sigemptyset(&action.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, s);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaction(s, &action, nullptr);
}

}  // namespace alloycolor
