// Elements, alloy systems and compositions. A composition is carried as x_atomic, the
// atomic (mole) fraction of element a of the system; weight fractions and karats are
// converted with standard atomic weights:
//   x_atomic = (w / M_a) / (w / M_a + (1 - w) / M_b).
// The free-electron density of the alloy assumes ideal mixing of molar volumes (Zen's
// law): N_e(x) = (x Z_a + (1-x) Z_b) N_A / (x V_a + (1-x) V_b), V = M / rho.
#ifndef ALLOYCOLOR_CORE_COMPOSITION_H_
#define ALLOYCOLOR_CORE_COMPOSITION_H_

#include <string>

namespace alloycolor {

struct Element {
  const char* symbol;
  double atomic_mass;    // g/mol, IUPAC standard atomic weight (abridged)
  double density_g_cm3;  // at room temperature
  double valence;        // free electrons per atom (Drude)
};

// Throws Error("unknown element 'Xx'") for a symbol not in the table.
const Element& FindElement(const std::string& symbol);

struct AlloySystem {
  Element a;
  Element b;
  std::string Name() const;  // "Au-Ag"
};

double AtomicFromWeightFraction(double w_a, const AlloySystem& system);
double WeightFromAtomicFraction(double x_a, const AlloySystem& system);

// Parses a composition of element a as written on a command line: an atomic fraction
// ("0.75"), atomic percent ("75at%"), weight percent ("75wt%") or, for gold alloys, a
// karat ("18k": 18/24 of the weight is gold). Returns x_atomic; throws Error naming the
// text when it cannot be read or lies outside [0, 1].
double ParseComposition(const std::string& text, const AlloySystem& system);

// Free-electron density in m^-3 at atomic fraction x_a.
double FreeElectronDensityM3(double x_a, const AlloySystem& system);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_COMPOSITION_H_
