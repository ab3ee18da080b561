// The physical model's eps over a wavelength grid at one set of parameter values, in SIMD
// lanes: what PhysicalModel and its bound model (AlloyModel::Bind) evaluate with. The terms are the
// templated physics of physical_model.h, instantiated on a scalar of this file (kernel::Lane) whose
// logarithm and arctangent are polynomial approximations that the compiler vectorises, in loops
// over the grid built for AVX-512, AVX2 and the x86-64 baseline (core/simd.h).
//
// Accuracy. ln x (x normal) and atan2 agree with the C library's to a few units in the
// last place (|error| < 1e-15 relative to the result, 5e-16 absolute for atan2; tested in
// tests/physical_kernel_test.cc), so eps agrees with PhysicalPermittivity to about 1e-14
// relative. Where an intermediate leaves the range those approximations cover (a logarithm
// of 0, of a subnormal, infinite or NaN number) the lane gives NaN, and the caller
// evaluates that composition the straightforward way (PhysicalModel: then eps is exactly
// what PhysicalPermittivity gives, finite or not).
//
// Cost, Au-Ag's drude + rioux-gap + rioux-edge model on the 95 wavelengths of the colour
// grid: docs/performance.md (bench/colour_bench.cc, beside the straightforward loop).
#ifndef ALLOYCOLOR_MODEL_PHYSICAL_KERNEL_H_
#define ALLOYCOLOR_MODEL_PHYSICAL_KERNEL_H_

#include <cstddef>

#include "alloycolor/model/physical_model.h"

namespace alloycolor::kernel {

// eps1[i] + i eps2[i] = eps at photon energies omega_ev[0..m) for the parameter values
// (layout order); at least one NaN where the approximations do not apply (above).
void PhysicalPermittivityOnGrid(const PhysicalLayout& layout, const double* values, std::size_t m,
                                const double* omega_ev, double* eps1, double* eps2);

// PhysicalPermittivityOnGrid with eps's derivatives with respect to the parameter values
// (physical_terms.h's gradients): grad1[k * m + i] + i grad2[k * m + i] = d eps / d value_k
// at omega_ev[i]. At least one NaN among eps where the approximations do not apply.
void PhysicalGradientOnGrid(const PhysicalLayout& layout, const double* values, std::size_t m,
                            const double* omega_ev, double* eps1, double* eps2, double* grad1,
                            double* grad2);

// Whether every eps1[i] + i eps2[i] is usable (UsablePermittivity: finite, not 0, within
// kMaxUsablePermittivity).
bool AllUsable(std::size_t m, const double* eps1, const double* eps2);

// ln x for x > 0 and atan2(y, x), as the lanes compute them (for the tests).
double LaneLog(double x);
double LaneAtan2(double y, double x);

}  // namespace alloycolor::kernel

#endif  // ALLOYCOLOR_MODEL_PHYSICAL_KERNEL_H_
