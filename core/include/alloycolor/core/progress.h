// How long work reports progress: the library calls a ProgressCallback (which may be
// empty) with one line of text; the program decides whether and how to show it.
//
// How long work is stopped: it calls a CancelCheck (which may be empty) between its steps —
// a fit's folds, candidates and solver iterations, a validation's splits, a table's or a
// picture's blocks of rows, a scan's points — from whichever of its threads reaches the
// step, so a check must be cheap and thread-safe (the Python package's reads an atomic
// flag its Ctrl-C sets). To stop the work, the check throws (Cancelled): the exception
// leaves every step as a progress callback's does, every thread of the work stops at its
// next check, and nothing is left half-written (outputs are written only once the work is
// done, core/output.h). A step that records an Error and goes on never catches it.
#ifndef ALLOYCOLOR_CORE_PROGRESS_H_
#define ALLOYCOLOR_CORE_PROGRESS_H_

#include <exception>
#include <functional>
#include <string>

namespace alloycolor {

using ProgressCallback = std::function<void(const std::string& message)>;

// Calls `progress` with `message` when it is set.
inline void Report(const ProgressCallback& progress, const std::string& message) {
  if (progress) progress(message);
}

using CancelCheck = std::function<void()>;

// What a CancelCheck throws to stop the work (not an alloycolor::Error: no step records it
// as a failure and goes on).
struct Cancelled : std::exception {
  const char* what() const noexcept override { return "the work was cancelled"; }
};

// Calls `cancel` when it is set: a step of long work is done.
inline void CheckCancel(const CancelCheck& cancel) {
  if (cancel) cancel();
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_PROGRESS_H_
