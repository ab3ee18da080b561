// Elements, alloy systems and compositions. A composition is carried as x_atomic, the
// atomic (mole) fraction of element a of the system; weight fractions and karats are
// converted with standard atomic weights:
//   x_atomic = (w / M_a) / (w / M_a + (1 - w) / M_b).
// The free-electron density of the alloy assumes ideal mixing of molar volumes (Zen's
// law): N_e(x) = (x Z_a + (1-x) Z_b) N_A / (x V_a + (1-x) V_b), V = M / rho.
//
// The element table (composition.cc) holds every metallic element with a standard atomic
// weight and the semimetals alloyed with them (B, Si, Ge, As, Sb, Se, Te, Bi):
//  - atomic_mass: IUPAC/CIAAW standard atomic weights 2021 (Prohaska et al., Pure Appl.
//    Chem. 94, 573 (2022)); where the standard weight is an interval (Li, B, Mg, Si, Tl,
//    Pb) the abridged/conventional value of the same table;
//  - density_g_cm3: CRC Handbook of Chemistry and Physics (97th ed.), section 4,
//    "Physical Constants of Inorganic Compounds", at room temperature;
//  - valence Z: Ashcroft & Mermin, Solid State Physics (1976), Table 1.1, where it lists
//    the element; otherwise a convention, flagged by valence_conventional: one s-like
//    conduction electron for d- and f-block metals (as Table 1.1 gives for Nb), the
//    group valence (s + p electrons) for the p-block elements.
// Only m* (through N_e) depends on the valence; n, k and colour never do, so no element
// is refused for the lack of one. A data set may override any of the three numbers.
#ifndef ALLOYCOLOR_CORE_COMPOSITION_H_
#define ALLOYCOLOR_CORE_COMPOSITION_H_

#include <cstddef>
#include <string>
#include <vector>

namespace alloycolor {

struct Element {
  const char* symbol;
  double atomic_mass;    // g/mol, IUPAC standard atomic weight (abridged)
  double density_g_cm3;  // at room temperature
  double valence;        // free electrons per atom (Drude)
  // True when the valence is the documented convention above rather than a value from
  // Ashcroft & Mermin Table 1.1 or from the data set: every m* read-out should say so.
  bool valence_conventional;
};

// Throws Error("unknown element 'Xx'") for a symbol not in the table.
const Element& FindElement(const std::string& symbol);

// Every element of the table, in order of atomic number.
std::vector<Element> KnownElements();

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
// text when it cannot be read, lies outside [0, 1] or is longer than
// kMaxCompositionChars (the explorer page's parser, export/explore/input.js, follows the
// same rules and bound: tests/reference/compositions.txt is the list both are tested on).
inline constexpr std::size_t kMaxCompositionChars = 64;
double ParseComposition(const std::string& text, const AlloySystem& system);

// A list of compositions split at its commas, `parts`, of which parts[failed] could not
// be read: when it and a neighbour are the two halves of a number written with a decimal
// comma ("0,75" split as "0" and "75"), the composition meant ("0.75"), else "".
std::string DecimalCommaReading(const std::vector<std::string>& parts, std::size_t failed,
                                const AlloySystem& system);

// Whether one of the two elements is gold, and the karat (24 x the weight fraction of
// gold) at atomic fraction x_a: the inverse of ParseComposition's "18k"; NaN otherwise.
bool IsGoldAlloy(const AlloySystem& system);
double KaratFromAtomicFraction(double x_a, const AlloySystem& system);

// Free-electron density in m^-3 at atomic fraction x_a.
double FreeElectronDensityM3(double x_a, const AlloySystem& system);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_COMPOSITION_H_
