// The one error type of alloycolor. Its message names the file, line, field or sample at
// fault, in one line, so the program can print it as it is and exit with status 2.
#ifndef ALLOYCOLOR_CORE_ERROR_H_
#define ALLOYCOLOR_CORE_ERROR_H_

#include <stdexcept>
#include <string>

namespace alloycolor {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_ERROR_H_
