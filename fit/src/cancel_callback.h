// Between a Ceres solve's iterations, the job's cancel check (core/progress.h): its exception
// is kept and the solve aborted (Ceres is not unwound through), then rethrown once Solve has
// returned, so the fit stops within one iteration.
#ifndef ALLOYCOLOR_FIT_CANCEL_CALLBACK_H_
#define ALLOYCOLOR_FIT_CANCEL_CALLBACK_H_

#include <ceres/ceres.h>

#include <exception>

#include "alloycolor/core/progress.h"

namespace alloycolor::fit {

class CancelCallback : public ceres::IterationCallback {
 public:
  // Adds itself to `options` when `cancel` is set; both must outlive the solve.
  CancelCallback(const CancelCheck& cancel, ceres::Solver::Options* options) : cancel_(cancel) {
    if (cancel_) options->callbacks.push_back(this);
  }
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    try {
      cancel_();
    } catch (...) {
      error_ = std::current_exception();
      return ceres::SOLVER_ABORT;
    }
    return ceres::SOLVER_CONTINUE;
  }
  // After the solve: what the check threw, if it did.
  void Rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  const CancelCheck& cancel_;
  std::exception_ptr error_;
};

}  // namespace alloycolor::fit

#endif  // ALLOYCOLOR_FIT_CANCEL_CALLBACK_H_
