#include "output_guard.h"

#include <signal.h>

#include <atomic>
#include <cstring>
#include <iostream>

#include "alloycolor/core/error.h"

namespace alloycolor::app {
namespace {

// The guard the signal handlers clean up after: set while a ProgramOutputGuard lives.
std::atomic<OutputGuard*> g_program_guard{nullptr};

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void RemoveTemporariesAndRaise(int signal_number) {
  if (const OutputGuard* guard = g_program_guard.load()) guard->RemoveTemporaries();
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

void NoteInputs(const Dataset& dataset) {
  NoteInput(dataset.manifest_path);
  for (const Sample& sample : dataset.samples) {
    NoteInput(sample.path);
    NoteInput(sample.k_path);
  }
}

void CheckOutputPath(const std::string& path) {
  alloycolor::CheckOutputPath(path, &ProgramGuard());
}

void PrintOutput(const std::string& text) {
  std::cout.flush();
  WriteStandardOutput(text);
}

}  // namespace alloycolor::app
