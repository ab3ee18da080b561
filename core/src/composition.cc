#include "alloycolor/core/composition.h"

#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "alloycolor/core/error.h"
#include "alloycolor/core/text.h"
#include "alloycolor/core/units.h"

namespace alloycolor {
namespace {

// The element table; sources and the valence convention are in composition.h.
//  - atomic_mass: CIAAW 2021 standard atomic weights; conventional (abridged) values for
//    the interval elements Li, B, Mg, Si, Tl, Pb.
//  - density_g_cm3: CRC Handbook, section 4, room temperature. Sn is white (beta) tin,
//    As grey arsenic, Se grey selenium, B beta-rhombohedral boron, Hg the liquid at 25 C.
//  - valence: kAM = Ashcroft & Mermin Table 1.1 (Li, Na, K, Rb, Cs, Cu, Ag, Au, Be, Mg, Ca,
//    Sr, Ba, Nb, Fe, Mn, Zn, Cd, Hg, Al, Ga, In, Tl, Sn, Pb, Bi, Sb); kConv = convention
//    (1 for d- and f-block metals, the group valence for the p block).
// Elements without a standard atomic weight (Tc, Pm, Po and the heavier actinides) are
// absent: a data set naming one must give its atomic_mass and density_g_cm3.
constexpr bool kAM = false;   // valence from Ashcroft & Mermin
constexpr bool kConv = true;  // conventional valence
// clang-format off
constexpr Element kElements[] = {
    // symbol, g/mol,       g/cm^3, Z, source of Z
    {"Li", 6.94,         0.534,  1, kAM},
    {"Be", 9.0121831,    1.85,   2, kAM},
    {"B",  10.81,        2.34,   3, kConv},
    {"Na", 22.98976928,  0.971,  1, kAM},
    {"Mg", 24.305,       1.74,   2, kAM},
    {"Al", 26.9815384,   2.70,   3, kAM},
    {"Si", 28.085,       2.3296, 4, kConv},
    {"K",  39.0983,      0.89,   1, kAM},
    {"Ca", 40.078,       1.54,   2, kAM},
    {"Sc", 44.955907,    2.99,   1, kConv},
    {"Ti", 47.867,       4.506,  1, kConv},
    {"V",  50.9415,      6.0,    1, kConv},
    {"Cr", 51.9961,      7.15,   1, kConv},
    {"Mn", 54.938043,    7.3,    2, kAM},
    {"Fe", 55.845,       7.874,  2, kAM},
    {"Co", 58.933194,    8.86,   1, kConv},
    {"Ni", 58.6934,      8.90,   1, kConv},
    {"Cu", 63.546,       8.96,   1, kAM},
    {"Zn", 65.38,        7.134,  2, kAM},
    {"Ga", 69.723,       5.91,   3, kAM},
    {"Ge", 72.630,       5.3234, 4, kConv},
    {"As", 74.921595,    5.75,   5, kConv},
    {"Se", 78.971,       4.81,   6, kConv},
    {"Rb", 85.4678,      1.53,   1, kAM},
    {"Sr", 87.62,        2.64,   2, kAM},
    {"Y",  88.905838,    4.47,   1, kConv},
    {"Zr", 91.224,       6.52,   1, kConv},
    {"Nb", 92.90637,     8.57,   1, kAM},
    {"Mo", 95.95,        10.2,   1, kConv},
    {"Ru", 101.07,       12.1,   1, kConv},
    {"Rh", 102.90549,    12.4,   1, kConv},
    {"Pd", 106.42,       12.0,   1, kConv},
    {"Ag", 107.8682,     10.5,   1, kAM},
    {"Cd", 112.414,      8.69,   2, kAM},
    {"In", 114.818,      7.31,   3, kAM},
    {"Sn", 118.710,      7.287,  4, kAM},
    {"Sb", 121.760,      6.68,   5, kAM},
    {"Te", 127.60,       6.232,  6, kConv},
    {"Cs", 132.90545196, 1.93,   1, kAM},
    {"Ba", 137.327,      3.62,   2, kAM},
    {"La", 138.90547,    6.15,   1, kConv},
    {"Ce", 140.116,      6.770,  1, kConv},
    {"Pr", 140.90766,    6.77,   1, kConv},
    {"Nd", 144.242,      7.01,   1, kConv},
    {"Sm", 150.36,       7.52,   1, kConv},
    {"Eu", 151.964,      5.24,   1, kConv},
    {"Gd", 157.25,       7.90,   1, kConv},
    {"Tb", 158.925354,   8.23,   1, kConv},
    {"Dy", 162.500,      8.55,   1, kConv},
    {"Ho", 164.930329,   8.80,   1, kConv},
    {"Er", 167.259,      9.07,   1, kConv},
    {"Tm", 168.934219,   9.32,   1, kConv},
    {"Yb", 173.045,      6.90,   1, kConv},
    {"Lu", 174.9668,     9.84,   1, kConv},
    {"Hf", 178.486,      13.3,   1, kConv},
    {"Ta", 180.94788,    16.4,   1, kConv},
    {"W",  183.84,       19.3,   1, kConv},
    {"Re", 186.207,      20.8,   1, kConv},
    {"Os", 190.23,       22.59,  1, kConv},
    {"Ir", 192.217,      22.56,  1, kConv},
    {"Pt", 195.084,      21.5,   1, kConv},
    {"Au", 196.966570,   19.3,   1, kAM},
    {"Hg", 200.592,      13.5336, 2, kAM},
    {"Tl", 204.38,       11.8,   3, kAM},
    {"Pb", 207.2,        11.3,   4, kAM},
    {"Bi", 208.98040,    9.79,   5, kAM},
    {"Th", 232.0377,     11.7,   1, kConv},
    {"Pa", 231.03588,    15.4,   1, kConv},
    {"U",  238.02891,    19.1,   1, kConv},
};
// clang-format on

void CheckFraction(double fraction, const char* what) {
  if (!(fraction >= 0 && fraction <= 1)) {
    Fail(std::string(what) + " " + FormatNumber(fraction) + " lies outside [0, 1]");
  }
}

// The forms ParseComposition reads, for its messages.
constexpr const char* kAcceptedForms =
    "accepted: an atomic fraction like 0.75, 75at%, 75wt%, or a karat like 18k for gold alloys";

// The accepted spelling of a composition written close to one of the accepted forms
// ("75wt" -> "75wt%", "75%wt" -> "75wt%", "18ct" -> "18k"), or "" when there is none.
// `lower` is the trimmed text in lower case.
std::string CloseForm(std::string_view lower) {
  const std::size_t end = lower.find_first_not_of("0123456789.+-");
  if (end == 0 || end == std::string_view::npos) return "";
  double value = 0;
  if (!ParseFiniteDouble(lower.substr(0, end), &value)) return "";
  std::string suffix;
  for (const char c : lower.substr(end)) {
    if (c != ' ' && c != '\t' && c != '.' && c != '-') suffix += c;
  }
  struct Spelling {
    const char* written;
    const char* accepted;
  };
  constexpr Spelling kSpellings[] = {
      {"wt", "wt%"},  {"%wt", "wt%"}, {"w%", "wt%"},  {"wt%", "wt%"},  {"at", "at%"},
      {"%at", "at%"}, {"a%", "at%"},  {"at%", "at%"}, {"mol%", "at%"}, {"ct", "k"},
      {"karat", "k"}, {"carat", "k"}, {"kt", "k"},    {"k", "k"}};
  for (const Spelling& s : kSpellings) {
    if (suffix == s.written) return std::string(lower.substr(0, end)) + s.accepted;
  }
  return "";
}

// Refuses text that is not a composition, naming the forms accepted and the closest.
[[noreturn]] void FailUnreadable(const std::string& quoted, std::string_view lower) {
  const std::string close = CloseForm(lower);
  Fail(quoted + (close.empty() ? ": cannot read it" : ": did you mean " + close + "?") + " (" +
       kAcceptedForms + ")");
}

}  // namespace

const Element& FindElement(const std::string& symbol) {
  for (const Element& element : kElements) {
    if (symbol == element.symbol) return element;
  }
  Fail("unknown element " + Quote(symbol));
}

std::vector<Element> KnownElements() {
  return std::vector<Element>(std::begin(kElements), std::end(kElements));
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

namespace {
bool IsGold(const Element& element) { return std::string_view(element.symbol) == "Au"; }
}  // namespace

double ParseComposition(const std::string& text, const AlloySystem& system) {
  const std::string_view trimmed = Trim(text);
  const std::string quoted = "composition " + Quote(text);
  if (trimmed.size() > kMaxCompositionChars) {
    Fail(quoted + " is " + std::to_string(trimmed.size()) + " characters long; a composition " +
         "has at most " + std::to_string(kMaxCompositionChars) + " (" + kAcceptedForms + ")");
  }
  std::string lower(trimmed);
  for (char& c : lower) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  const std::string_view view(lower);
  double value = 0;
  const auto number = [&](std::size_t suffix_length) {
    if (!ParseFiniteDouble(Trim(view.substr(0, view.size() - suffix_length)), &value)) {
      FailUnreadable(quoted, view);
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
    const std::string close = CloseForm(view);
    if (!close.empty()) FailUnreadable(quoted, view);
    Fail(quoted + " is ambiguous: write at% (atomic) or wt% (weight)");
  }
  if (EndsWith(view, "kt") || EndsWith(view, "k")) {
    number(EndsWith(view, "kt") ? 2 : 1);
    const bool a_is_gold = IsGold(system.a);
    const bool b_is_gold = IsGold(system.b);
    if (!a_is_gold && !b_is_gold) {
      Fail(quoted + ": karats apply to gold alloys only, not to " + system.Name());
    }
    if (!(value >= 0 && value <= 24)) Fail(quoted + " lies outside 0 to 24 karat");
    const double w_gold = value / 24;
    return AtomicFromWeightFraction(a_is_gold ? w_gold : 1 - w_gold, system);
  }
  if (view.empty()) Fail("empty composition");
  number(0);
  if (value > 1 && value <= 100) {
    const std::string written(view);
    Fail(quoted + " lies outside [0, 1] (an atomic fraction); did you mean " + written + "at% or " +
         written + "wt%?");
  }
  if (!(value >= 0 && value <= 1)) {
    Fail(quoted + " lies outside [0, 1] (an atomic fraction; write at% or wt% for percent)");
  }
  return value;
}

std::string DecimalCommaReading(const std::vector<std::string>& parts, std::size_t failed,
                                const AlloySystem& system) {
  const auto digits = [](std::string_view t) {
    return !t.empty() && t.find_first_not_of("0123456789") == std::string_view::npos;
  };
  const auto starts_with_digit = [](std::string_view t) {
    return !t.empty() && t.front() >= '0' && t.front() <= '9';
  };
  // (integer part, fraction part) pairs that take in the part that failed.
  for (const std::size_t left : {failed - 1, failed}) {
    if (failed == 0 && left != failed) continue;
    if (left + 1 >= parts.size()) continue;
    const std::string_view whole = Trim(parts[left]), fraction = Trim(parts[left + 1]);
    if (!digits(whole) || !starts_with_digit(fraction)) continue;
    const std::string joined = std::string(whole) + "." + std::string(fraction);
    try {
      ParseComposition(joined, system);
      return joined;
    } catch (const Error&) {
    }
  }
  return "";
}

bool IsGoldAlloy(const AlloySystem& system) { return IsGold(system.a) || IsGold(system.b); }

double KaratFromAtomicFraction(double x_a, const AlloySystem& system) {
  if (!IsGoldAlloy(system)) return std::numeric_limits<double>::quiet_NaN();
  const double w_a = WeightFromAtomicFraction(x_a, system);
  return 24 * (IsGold(system.a) ? w_a : 1 - w_a);
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
