#include "alloycolor/core/composition.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <system_error>

#include "alloycolor/core/error.h"
#include "alloycolor/core/units.h"

namespace alloycolor {
namespace {

// The elements the library knows: only those with a sourced value in every column.
//  - atomic_mass: IUPAC standard atomic weights (CIAAW, 2021 table; for Mg and Pb, whose
//    standard weight is an interval, the IUPAC abridged/conventional value).
//  - density_g_cm3: CRC Handbook of Chemistry and Physics, section 4 ("Physical Constants
//    of Inorganic Compounds"), at room temperature; Sn is white (beta) tin.
//  - valence: free electrons per atom Z as listed by Ashcroft & Mermin, Solid State
//    Physics (1976), Table 1.1 ("Free electron densities of selected elements"). For Nb
//    it gives Z = 1, the value commonly taken for Drude fits (one s-like conduction
//    electron; the group valence 5 counts the d electrons, which do not behave as free
//    electrons), and we follow it. Transition metals such as Ni, Pd, Pt, Cr, Ti, Co, Rh,
//    Ir, Ta, W, Mo and V have no free-electron valence in that table, so they are left
//    out rather than given an invented one.
// clang-format off
constexpr Element kElements[] = {
    // symbol, g/mol,    g/cm^3, Z
    {"Ag", 107.8682,   10.5,   1},
    {"Al", 26.9815384, 2.70,   3},
    {"Au", 196.966570, 19.3,   1},
    {"Cu", 63.546,     8.96,   1},
    {"Fe", 55.845,     7.874,  2},
    {"Ga", 69.723,     5.91,   3},
    {"In", 114.818,    7.31,   3},
    {"Mg", 24.305,     1.74,   2},
    {"Nb", 92.90637,   8.57,   1},
    {"Pb", 207.2,      11.3,   4},
    {"Sn", 118.710,    7.287,  4},
    {"Zn", 65.38,      7.134,  2},
};
// clang-format on

[[noreturn]] void Fail(std::string message) {
  for (char& c : message) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  throw Error(message);
}

std::string Number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.10g", value);
  return buffer;
}

// Text from the user quoted in a message: at most 40 characters.
std::string Quote(std::string_view text) {
  constexpr std::size_t kMax = 40;
  if (text.size() <= kMax) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kMax)) + "...'";
}

std::string_view Trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

bool EndsWith(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

// A finite number in the C locale, the whole text.
bool ParseDouble(std::string_view token, double* value) {
  const bool plus = !token.empty() && token.front() == '+';
  if (plus) token.remove_prefix(1);
  if (token.empty() || (plus && token.front() == '-')) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end && std::isfinite(*value);
}

void CheckFraction(double fraction, const char* what) {
  if (!(fraction >= 0 && fraction <= 1)) {
    Fail(std::string(what) + " " + Number(fraction) + " lies outside [0, 1]");
  }
}

}  // namespace

const Element& FindElement(const std::string& symbol) {
  for (const Element& element : kElements) {
    if (symbol == element.symbol) return element;
  }
  Fail("unknown element " + Quote(symbol));
}

std::string AlloySystem::Name() const {
  return std::string(a.symbol) + "-" + std::string(b.symbol);
}

double AtomicFromWeightFraction(double w_a, const AlloySystem& system) {
  CheckFraction(w_a, "weight fraction");
  const double moles_a = w_a / system.a.atomic_mass;
  const double moles_b = (1 - w_a) / system.b.atomic_mass;
  return moles_a / (moles_a + moles_b);
}

double WeightFromAtomicFraction(double x_a, const AlloySystem& system) {
  CheckFraction(x_a, "atomic fraction");
  const double mass_a = x_a * system.a.atomic_mass;
  const double mass_b = (1 - x_a) * system.b.atomic_mass;
  return mass_a / (mass_a + mass_b);
}

double ParseComposition(const std::string& text, const AlloySystem& system) {
  const std::string_view trimmed = Trim(text);
  const std::string quoted = "composition " + Quote(text);
  std::string lower(trimmed);
  for (char& c : lower) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  const std::string_view view(lower);
  double value = 0;
  const auto number = [&](std::size_t suffix_length) {
    if (!ParseDouble(Trim(view.substr(0, view.size() - suffix_length)), &value)) {
      Fail(quoted + ": cannot read the number");
    }
  };
  if (EndsWith(view, "at%")) {
    number(3);
    if (!(value >= 0 && value <= 100)) Fail(quoted + " lies outside 0 to 100 at%");
    return value / 100;
  }
  if (EndsWith(view, "wt%")) {
    number(3);
    if (!(value >= 0 && value <= 100)) Fail(quoted + " lies outside 0 to 100 wt%");
    return AtomicFromWeightFraction(value / 100, system);
  }
  if (EndsWith(view, "%")) {
    Fail(quoted + " is ambiguous: write at% (atomic) or wt% (weight)");
  }
  if (EndsWith(view, "kt") || EndsWith(view, "k")) {
    number(EndsWith(view, "kt") ? 2 : 1);
    const bool a_is_gold = std::string_view(system.a.symbol) == "Au";
    const bool b_is_gold = std::string_view(system.b.symbol) == "Au";
    if (!a_is_gold && !b_is_gold) {
      Fail(quoted + ": karats apply to gold alloys only, not to " + system.Name());
    }
    if (!(value >= 0 && value <= 24)) Fail(quoted + " lies outside 0 to 24 karat");
    const double w_gold = value / 24;
    return AtomicFromWeightFraction(a_is_gold ? w_gold : 1 - w_gold, system);
  }
  if (view.empty()) Fail("empty composition");
  number(0);
  if (!(value >= 0 && value <= 1)) {
    Fail(quoted + " lies outside [0, 1] (an atomic fraction; write at% or wt% for percent)");
  }
  return value;
}

double FreeElectronDensityM3(double x_a, const AlloySystem& system) {
  CheckFraction(x_a, "atomic fraction");
  constexpr double kM3PerCm3 = 1e-6;
  const double valence = x_a * system.a.valence + (1 - x_a) * system.b.valence;
  const double molar_volume_a = system.a.atomic_mass / system.a.density_g_cm3;
  const double molar_volume_b = system.b.atomic_mass / system.b.density_g_cm3;
  const double molar_volume_cm3 = x_a * molar_volume_a + (1 - x_a) * molar_volume_b;
  return valence * kAvogadro / (molar_volume_cm3 * kM3PerCm3);
}

}  // namespace alloycolor
