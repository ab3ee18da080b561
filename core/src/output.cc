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

void InstallTemporaryCleanup() {
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = RemoveTemporariesAndRaise;
  sigemptyset(&action.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&action.sa_mask, s);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaction(s, &action, nullptr);
}

}  // namespace alloycolor
