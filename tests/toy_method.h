// A method added from outside the library, as docs/architecture.md tells: this file pair
// and the one registration at the end of toy_method.cc, nothing else. Linked into a test
// (toy_method_test.cc), into the program (alloycolor_toy, app/main.cc with this file) and
// into the Python module (tests/toy_python), it is fitted, listed, checked and validated
// by the same code as the built-in methods.
//
// "toy-constant": eps(lambda, x) = eps1 + i, the same at every wavelength and composition,
// eps1 its one option (toy_eps1, --toy-eps1: a finite number in [-100, -0.01], default -10:
// a metal's eps1 is negative). It says it is not a candidate of auto (auto_rank -1), so an
// auto fit refuses its option by name, and validate runs it only when asked.
#ifndef ALLOYCOLOR_TESTS_TOY_METHOD_H_
#define ALLOYCOLOR_TESTS_TOY_METHOD_H_

namespace alloycolor::toy {

inline constexpr const char* kMethod = "toy-constant";
inline constexpr const char* kOption = "toy_eps1";
inline constexpr const char* kFlag = "--toy-eps1";
inline constexpr double kEps2 = 1.0;  // eps2, fixed

}  // namespace alloycolor::toy

#endif  // ALLOYCOLOR_TESTS_TOY_METHOD_H_
