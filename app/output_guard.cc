#include "output_guard.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <system_error>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"

namespace alloycolor::app {
namespace {

// The guard the signal handlers clean up after: set while a ProgramOutputGuard lives.
std::atomic<OutputGuard*> g_program_guard{nullptr};

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

// The folders CreateOutputFolder made, outermost first, in fixed slots (a signal handler
// reads them: no allocation there); a path too long for a slot is not tracked.
constexpr int kFolderSlots = 32;
constexpr std::size_t kFolderBytes = 4096;
char g_created_folders[kFolderSlots][kFolderBytes];
std::atomic<int> g_created_count{0};

// rmdir, deepest first: only folders still empty go. Async-signal-safe.
void RemoveEmptyCreatedFolders() noexcept {
  for (int i = g_created_count.load(); i-- > 0;) rmdir(g_created_folders[i]);
}

extern "C" void RemoveTemporariesAndRaise(int signal_number) {
  if (const OutputGuard* guard = g_program_guard.load()) guard->RemoveTemporaries();
  RemoveEmptyCreatedFolders();
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  sigaction(signal_number, &action, nullptr);
  raise(signal_number);
}

void SetDisposition(int signal_number, void (*handler)(int)) {
  struct sigaction action;
  std::memset(&action, 0, sizeof(action));
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  for (int s : kCleanupSignals) sigaddset(&action.sa_mask, s);
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

ProgramOutputGuard::ProgramOutputGuard() {
  g_program_guard.store(&guard_);
  // Errors on write, not signals that kill the program half-way.
  SetDisposition(SIGPIPE, SIG_IGN);
  SetDisposition(SIGXFSZ, SIG_IGN);
  for (int s : kCleanupSignals) SetDisposition(s, RemoveTemporariesAndRaise);
}

ProgramOutputGuard::~ProgramOutputGuard() {
  for (int s : kCleanupSignals) SetDisposition(s, SIG_DFL);
  RemoveEmptyCreatedFolders();  // a command that failed before writing into them
  g_created_count.store(0);
  g_program_guard.store(nullptr);
}

OutputGuard& ProgramGuard() {
  OutputGuard* guard = g_program_guard.load();
  if (!guard) throw Error("internal: no output guard (main makes one)");
  return *guard;
}

void NoteInput(const std::string& path) {
  if (!path.empty()) ProgramGuard().NoteInput(path);
}

void NoteInputs(const Dataset& dataset) { ProgramGuard().NoteInputs(dataset); }

void CheckOutputPath(const std::string& path) {
  alloycolor::CheckOutputPath(path, &ProgramGuard());
}

void CreateOutputFolder(const std::string& dir, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw Error(option + " " + Quote(dir, 200) + " exists and is not a folder");
  }
  // The missing levels, outermost first.
  std::vector<fs::path> missing;
  fs::path target = fs::path(dir).lexically_normal();
  if (target.filename().empty() && target.has_parent_path()) target = target.parent_path();
  for (fs::path p = target; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  for (const fs::path& p : missing) {
    if (!fs::create_directory(p, ec) && ec) {
      throw Error(option + ": cannot create folder " + Quote(p.string(), 200) + ": " +
                  ec.message());
    }
    const std::string path = p.string();
    const int slot = g_created_count.load();
    if (slot < kFolderSlots && path.size() < kFolderBytes) {
      std::memcpy(g_created_folders[slot], path.c_str(), path.size() + 1);
      g_created_count.store(slot + 1);
    }
  }
}

void PrintOutput(const std::string& text) {
  std::cout.flush();
  WriteStandardOutput(text);
}

}  // namespace alloycolor::app
