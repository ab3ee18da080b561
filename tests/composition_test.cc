// Tests of elements and compositions (model/composition.h) against hand calculations
// from the IUPAC atomic weights and CRC densities in the element table.
#include "alloycolor/core/composition.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "alloycolor/core/error.h"

namespace alloycolor {
namespace {

using ::testing::HasSubstr;

constexpr double kAuMass = 196.966570;  // IUPAC standard atomic weights
constexpr double kAgMass = 107.8682;
constexpr double kSnMass = 118.710;
constexpr double kNbMass = 92.90637;

AlloySystem System(const char* a, const char* b) { return {FindElement(a), FindElement(b)}; }

std::string ErrorOf(const std::string& text, const AlloySystem& system) {
  try {
    ParseComposition(text, system);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error for '" << text << "'";
  return "";
}

TEST(ElementTest, TableValues) {
  EXPECT_EQ(FindElement("Au").atomic_mass, kAuMass);
  EXPECT_EQ(FindElement("Ag").atomic_mass, kAgMass);
  EXPECT_EQ(FindElement("Au").valence, 1);
  EXPECT_EQ(FindElement("Zn").valence, 2);
  EXPECT_EQ(FindElement("Sn").valence, 4);
  EXPECT_EQ(FindElement("Nb").valence, 1);
  EXPECT_EQ(std::string(FindElement("Cu").symbol), "Cu");
  EXPECT_EQ(System("Au", "Ag").Name(), "Au-Ag");
}

TEST(ElementTest, UnknownElementIsAnError) {
  try {
    FindElement("Xx");
    FAIL() << "no Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown element 'Xx'"));
  }
  EXPECT_THROW(FindElement("au"), Error);  // symbols are case-sensitive
  EXPECT_THROW(FindElement(""), Error);
}

TEST(CompositionTest, EighteenKaratGoldWithSilver) {
  // w_Au = 18/24 = 0.75; x = (0.75 / M_Au) / (0.75 / M_Au + 0.25 / M_Ag) = 0.62163...
  const double by_hand = (0.75 / kAuMass) / (0.75 / kAuMass + 0.25 / kAgMass);
  const AlloySystem au_ag = System("Au", "Ag");
  EXPECT_NEAR(by_hand, 0.62163, 1e-5);
  EXPECT_NEAR(AtomicFromWeightFraction(0.75, au_ag), by_hand, 1e-14);
  for (const char* text : {"18k", "18K", "18kt", " 18 kt ", "75wt%", "75 wt%", "75WT%"}) {
    SCOPED_TRACE(text);
    EXPECT_NEAR(ParseComposition(text, au_ag), by_hand, 1e-14);
  }
  // With gold as element b the composition is that of silver: 1 - x_Au.
  EXPECT_NEAR(ParseComposition("18k", System("Ag", "Au")), 1 - by_hand, 1e-14);
  EXPECT_NEAR(ParseComposition("24k", au_ag), 1.0, 1e-15);
  EXPECT_NEAR(ParseComposition("0k", au_ag), 0.0, 1e-15);
}

TEST(CompositionTest, AtomicFractionAndPercent) {
  const AlloySystem au_ag = System("Au", "Ag");
  EXPECT_DOUBLE_EQ(ParseComposition("0.75", au_ag), 0.75);
  EXPECT_DOUBLE_EQ(ParseComposition("75at%", au_ag), 0.75);
  EXPECT_DOUBLE_EQ(ParseComposition("75 at%", au_ag), 0.75);
  EXPECT_DOUBLE_EQ(ParseComposition("1", au_ag), 1.0);
  EXPECT_DOUBLE_EQ(ParseComposition("0", au_ag), 0.0);
  EXPECT_DOUBLE_EQ(ParseComposition("+.5", au_ag), 0.5);
}

TEST(CompositionTest, WeightAtomicRoundTrip) {
  const AlloySystem sn_nb = System("Sn", "Nb");
  for (double w : {0.0, 0.06, 0.22, 0.5, 0.55, 0.999, 1.0}) {
    SCOPED_TRACE(w);
    EXPECT_NEAR(WeightFromAtomicFraction(AtomicFromWeightFraction(w, sn_nb), sn_nb), w, 1e-14);
  }
  // 6 wt% Sn in Nb, by hand: (0.06 / 118.710) / (0.06 / 118.710 + 0.94 / 92.90637).
  EXPECT_NEAR(AtomicFromWeightFraction(0.06, sn_nb), 0.0475785, 1e-7);
  const double x = (0.06 / kSnMass) / (0.06 / kSnMass + 0.94 / kNbMass);
  EXPECT_NEAR(AtomicFromWeightFraction(0.06, sn_nb), x, 1e-15);
  EXPECT_THROW(AtomicFromWeightFraction(1.5, sn_nb), Error);
  EXPECT_THROW(WeightFromAtomicFraction(-0.1, sn_nb), Error);
}

TEST(CompositionTest, BadTextIsNamed) {
  const AlloySystem au_ag = System("Au", "Ag");
  const AlloySystem cu_zn = System("Cu", "Zn");
  EXPECT_THAT(ErrorOf("18k", cu_zn), HasSubstr("'18k'"));
  EXPECT_THAT(ErrorOf("18k", cu_zn), HasSubstr("gold alloys only, not to Cu-Zn"));
  EXPECT_THAT(ErrorOf("75%", au_ag), HasSubstr("'75%' is ambiguous: write at%"));
  EXPECT_THAT(ErrorOf("75%", au_ag), HasSubstr("wt%"));
  EXPECT_THAT(ErrorOf("1.5", au_ag), HasSubstr("'1.5' lies outside [0, 1]"));
  EXPECT_THAT(ErrorOf("-0.1", au_ag), HasSubstr("'-0.1'"));
  EXPECT_THAT(ErrorOf("75", au_ag), HasSubstr("'75'"));
  EXPECT_THAT(ErrorOf("25k", au_ag), HasSubstr("'25k' lies outside 0 to 24 karat"));
  EXPECT_THAT(ErrorOf("101wt%", au_ag), HasSubstr("'101wt%'"));
  EXPECT_THAT(ErrorOf("-1at%", au_ag), HasSubstr("'-1at%'"));
  EXPECT_THAT(ErrorOf("abc", au_ag), HasSubstr("'abc'"));
  EXPECT_THAT(ErrorOf("nan", au_ag), HasSubstr("'nan'"));
  EXPECT_THAT(ErrorOf("inf", au_ag), HasSubstr("'inf'"));
  EXPECT_THAT(ErrorOf("0.5x", au_ag), HasSubstr("'0.5x'"));
  EXPECT_THAT(ErrorOf("wt%", au_ag), HasSubstr("'wt%'"));
  EXPECT_THAT(ErrorOf("k", au_ag), HasSubstr("'k'"));
  EXPECT_THAT(ErrorOf("", au_ag), HasSubstr("empty composition"));
}

// A composition written close to an accepted form gets the accepted spelling; any other
// gets the forms accepted.
TEST(CompositionTest, CloseMissesGetTheAcceptedSpelling) {
  const AlloySystem au_ag = System("Au", "Ag");
  const std::pair<const char*, const char*> cases[] = {
      {"75wt", "did you mean 75wt%?"},       {"75 wt", "did you mean 75wt%?"},
      {"75%wt", "did you mean 75wt%?"},      {"75wt.%", "did you mean 75wt%?"},
      {"50at", "did you mean 50at%?"},       {"50mol%", "did you mean 50at%?"},
      {"18ct", "did you mean 18k?"},         {"18 karat", "did you mean 18k?"},
      {"75", "did you mean 75at% or 75wt%?"}};
  for (const auto& [text, needle] : cases) {
    EXPECT_THAT(ErrorOf(text, au_ag), HasSubstr(needle)) << text;
  }
  const std::string abc = ErrorOf("abc", au_ag);
  EXPECT_THAT(abc, HasSubstr("accepted: an atomic fraction like 0.75, 75at%, 75wt%"));
  EXPECT_EQ(abc.find("did you mean"), std::string::npos) << abc;
  EXPECT_EQ(ErrorOf("200", au_ag).find("did you mean"), std::string::npos);
  // No option is named: the program adds its own.
  EXPECT_EQ(abc.find("--"), std::string::npos) << abc;
}

TEST(FreeElectronDensityTest, GoldMatchesAshcroftMermin) {
  // Ashcroft & Mermin, Table 1.1: gold, Z = 1, N_e = 5.90e22 cm^-3.
  const AlloySystem au_ag = System("Au", "Ag");
  EXPECT_NEAR(FreeElectronDensityM3(1.0, au_ag), 5.90e28, 0.01 * 5.90e28);
  // Silver: 5.86e22 cm^-3.
  EXPECT_NEAR(FreeElectronDensityM3(0.0, au_ag), 5.86e28, 0.01 * 5.86e28);
}

TEST(FreeElectronDensityTest, ZenLawByHand) {
  // Au50Ag50: Z = 1; V = 0.5 (196.966570 / 19.3) + 0.5 (107.8682 / 10.5) cm^3/mol.
  const double volume_cm3 = 0.5 * kAuMass / 19.3 + 0.5 * kAgMass / 10.5;
  const double by_hand = 6.02214076e23 / (volume_cm3 * 1e-6);
  EXPECT_NEAR(FreeElectronDensityM3(0.5, System("Au", "Ag")), by_hand, 1e-12 * by_hand);
  // Cu-Zn: Z mixes linearly too; pure zinc has Z = 2 (A&M: 13.2e22 cm^-3).
  EXPECT_NEAR(FreeElectronDensityM3(0.0, System("Cu", "Zn")), 13.2e28, 0.01 * 13.2e28);
  EXPECT_THROW(FreeElectronDensityM3(1.1, System("Cu", "Zn")), Error);
}

}  // namespace
}  // namespace alloycolor

namespace alloycolor {
namespace {

// Further metals, each with its standard atomic weight typed here from the CIAAW 2021
// table (conventional values for interval elements), independently of the library's table.
struct MetalMass {
  const char* symbol;
  double mass;
};
constexpr MetalMass kFurtherMetals[] = {
    {"Li", 6.94},      {"Be", 9.0121831}, {"Na", 22.98976928}, {"K", 39.0983},    {"Ca", 40.078},
    {"Sc", 44.955907}, {"Ti", 47.867},    {"V", 50.9415},      {"Cr", 51.9961},   {"Mn", 54.938043},
    {"Co", 58.933194}, {"Ni", 58.6934},   {"Ge", 72.630},      {"Sr", 87.62},     {"Y", 88.905838},
    {"Zr", 91.224},    {"Mo", 95.95},     {"Ru", 101.07},      {"Rh", 102.90549}, {"Pd", 106.42},
    {"Cd", 112.414},   {"Sb", 121.760},   {"Ba", 137.327},     {"La", 138.90547}, {"Ce", 140.116},
    {"Nd", 144.242},   {"Gd", 157.25},    {"Hf", 178.486},     {"Ta", 180.94788}, {"W", 183.84},
    {"Re", 186.207},   {"Os", 190.23},    {"Ir", 192.217},     {"Pt", 195.084},   {"Hg", 200.592},
    {"Tl", 204.38},    {"Bi", 208.98040}, {"Si", 28.085},      {"B", 10.81},      {"As", 74.921595},
    {"Te", 127.60},    {"U", 238.02891},
};

TEST(ElementTest, FurtherMetalsHaveTheirStandardAtomicWeights) {
  for (const MetalMass& metal : kFurtherMetals) {
    SCOPED_TRACE(metal.symbol);
    const Element& element = FindElement(metal.symbol);
    EXPECT_EQ(element.atomic_mass, metal.mass);
    EXPECT_GT(element.density_g_cm3, 0.5);
    EXPECT_LT(element.density_g_cm3, 23);
    EXPECT_GT(element.valence, 0);
    // wt% -> atomic fraction for Au-M, by hand: x = (w/M_Au) / (w/M_Au + (1-w)/M).
    const AlloySystem system{FindElement("Au"), element};
    for (const double w : {0.1, 0.5, 0.75}) {
      const double by_hand = (w / kAuMass) / (w / kAuMass + (1 - w) / metal.mass);
      EXPECT_NEAR(AtomicFromWeightFraction(w, system), by_hand, 1e-14);
      EXPECT_NEAR(WeightFromAtomicFraction(by_hand, system), w, 1e-14);
    }
  }
  EXPECT_GE(sizeof(kFurtherMetals) / sizeof(kFurtherMetals[0]), 26u);
}

TEST(ElementTest, ValenceFromAshcroftMerminOrFlaggedConvention) {
  // Ashcroft & Mermin Table 1.1.
  for (const auto& [symbol, z] : std::vector<std::pair<const char*, double>>{
           {"Li", 1}, {"Na", 1}, {"K", 1},  {"Cs", 1}, {"Cu", 1}, {"Ag", 1}, {"Au", 1},
           {"Be", 2}, {"Mg", 2}, {"Ca", 2}, {"Ba", 2}, {"Nb", 1}, {"Fe", 2}, {"Mn", 2},
           {"Zn", 2}, {"Cd", 2}, {"Hg", 2}, {"Al", 3}, {"Ga", 3}, {"In", 3}, {"Tl", 3},
           {"Sn", 4}, {"Pb", 4}, {"Bi", 5}, {"Sb", 5}}) {
    SCOPED_TRACE(symbol);
    EXPECT_EQ(FindElement(symbol).valence, z);
    EXPECT_FALSE(FindElement(symbol).valence_conventional);
  }
  // Not in the table: the documented convention, flagged.
  for (const char* symbol : {"Pd", "Pt", "Ni", "Ti", "Cr", "Co", "Rh", "Ir", "W", "Mo", "V"}) {
    SCOPED_TRACE(symbol);
    EXPECT_EQ(FindElement(symbol).valence, 1);
    EXPECT_TRUE(FindElement(symbol).valence_conventional);
  }
  EXPECT_EQ(FindElement("Si").valence, 4);
  EXPECT_EQ(FindElement("Ge").valence, 4);
  EXPECT_EQ(FindElement("As").valence, 5);
  EXPECT_EQ(FindElement("Te").valence, 6);
  EXPECT_EQ(FindElement("B").valence, 3);
  EXPECT_TRUE(FindElement("Ge").valence_conventional);
}

TEST(ElementTest, KnownElementsAreUniqueAndFindable) {
  const std::vector<Element> elements = KnownElements();
  EXPECT_GE(elements.size(), 65u);
  for (std::size_t i = 0; i < elements.size(); ++i) {
    EXPECT_EQ(&FindElement(elements[i].symbol), &FindElement(elements[i].symbol));
    EXPECT_EQ(FindElement(elements[i].symbol).atomic_mass, elements[i].atomic_mass);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(std::string(elements[i].symbol), elements[j].symbol);
    }
    // Atomic number order: masses rise except at Ni (58.69, after Co 58.93) and Pa
    // (231.04, after Th 232.04).
    const std::string symbol = elements[i].symbol;
    if (i > 0 && symbol != "Ni" && symbol != "Pa") {
      EXPECT_GT(elements[i].atomic_mass, elements[i - 1].atomic_mass) << elements[i].symbol;
    }
  }
}

TEST(CompositionTest, KaratsForWhiteGold) {
  // 18k Au-Pd: w_Au = 0.75; by hand x_Au = (0.75/196.96657) / (0.75/196.96657 +
  // 0.25/106.42) = 0.6184493758.
  const AlloySystem au_pd = System("Au", "Pd");
  EXPECT_NEAR(ParseComposition("18k", au_pd), 0.6184493758, 1e-10);
  EXPECT_NEAR(WeightFromAtomicFraction(ParseComposition("18k", au_pd), au_pd), 0.75, 1e-14);
  // 18k Au-Ni: x_Au = (0.75/196.96657) / (0.75/196.96657 + 0.25/58.6934) = 0.4720056952.
  EXPECT_NEAR(ParseComposition("18k", System("Au", "Ni")), 0.4720056952, 1e-10);
  EXPECT_NEAR(ParseComposition("18k", System("Pd", "Au")), 1 - 0.6184493758, 1e-10);
  EXPECT_THAT(ErrorOf("18k", System("Pd", "Ni")), HasSubstr("gold alloys only"));
  EXPECT_THAT(ErrorOf("18k", System("Pt", "Ir")), HasSubstr("not to Pt-Ir"));
}

}  // namespace
}  // namespace alloycolor
