// The program's output policy (core/output.h holds the mechanism, this file the process
// state): one OutputGuard owned by main for the life of the run, handed to every writer,
// and the signal dispositions that go with it:
//  - SIGINT, SIGTERM and SIGHUP unlink the temporaries in flight (OutputGuard::
//    RemoveTemporaries, async-signal-safe) and remove the output folders the command
//    created while they are empty (CreateOutputFolder), then take their default effect;
//  - SIGPIPE and SIGXFSZ are ignored, so that a closed pipe (EPIPE) and a file past
//    `ulimit -f` (EFBIG) reach the writer as errors: it removes its temporary and the
//    program prints one line naming the output, instead of dying with a partial file.
// The commands note their input files (NoteInput: --data's manifest and samples, --model,
// --nk, --from, the colour tables) so that no output replaces one of them.
#ifndef ALLOYCOLOR_APP_OUTPUT_GUARD_H_
#define ALLOYCOLOR_APP_OUTPUT_GUARD_H_

#include <string>

#include "alloycolor/core/dataset.h"
#include "alloycolor/core/output.h"

namespace alloycolor::app {

// Constructed once, by main, before any command runs: installs the dispositions above and
// becomes the guard ProgramGuard() returns; destroyed, it restores the defaults.
class ProgramOutputGuard {
 public:
  ProgramOutputGuard();
  ~ProgramOutputGuard();
  ProgramOutputGuard(const ProgramOutputGuard&) = delete;
  ProgramOutputGuard& operator=(const ProgramOutputGuard&) = delete;

  OutputGuard& guard() { return guard_; }

 private:
  OutputGuard guard_;
};

// The guard of the running program; throws Error when main made none.
OutputGuard& ProgramGuard();

// Notes an input file of the running command.
void NoteInput(const std::string& path);
// Notes a data set's manifest and every sample file it names (OutputGuard::NoteInputs).
void NoteInputs(const Dataset& dataset);

// Throws Error when `path` cannot be an output of this command (an input, a symlink, a
// device, a folder): core's CheckOutputPath with the program's guard.
void CheckOutputPath(const std::string& path);

// Creates the folder `dir` (and its missing parents) for this command's outputs, naming
// `option` when it cannot. The folders it made are the guard's until the program ends:
// a signal (SIGINT, SIGTERM, SIGHUP) removes them, deepest first, when they are still
// empty, and so does the end of the program (a command that failed before writing
// there), so that a report stopped half-way leaves no empty folder behind.
void CreateOutputFolder(const std::string& dir, const std::string& option);

// Writes `text` to standard output all or nothing (core's WriteStandardOutput), after
// whatever std::cout holds.
void PrintOutput(const std::string& text);

}  // namespace alloycolor::app

#endif  // ALLOYCOLOR_APP_OUTPUT_GUARD_H_
