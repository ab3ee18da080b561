// How long work reports progress: the library calls a ProgressCallback (which may be
// empty) with one line of text; the program decides whether and how to show it.
#ifndef ALLOYCOLOR_CORE_PROGRESS_H_
#define ALLOYCOLOR_CORE_PROGRESS_H_

#include <functional>
#include <string>

namespace alloycolor {

using ProgressCallback = std::function<void(const std::string& message)>;

// Calls `progress` with `message` when it is set.
inline void Report(const ProgressCallback& progress, const std::string& message) {
  if (progress) progress(message);
}

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_PROGRESS_H_
