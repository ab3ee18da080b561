// Physical constants and unit conversions (CODATA 2018 exact or recommended values).
// Energies are photon energies in eV: omega_eV = hbar * omega; gamma_eV = hbar / tau.
#ifndef ALLOYCOLOR_CORE_UNITS_H_
#define ALLOYCOLOR_CORE_UNITS_H_

namespace alloycolor {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kHcEvNm = 1239.8419843320026;    // h c in eV nm
inline constexpr double kHbarEvFs = 0.6582119569509066;  // hbar in eV fs
inline constexpr double kAvogadro = 6.02214076e23;       // 1/mol
// e^2 hbar^2 / (eps0 m_e) in eV^2 m^3: (hbar omega_p)^2 = kPlasmaEv2M3 * N_e / (m*/m_e).
inline constexpr double kPlasmaEv2M3 = 1.3788422950858569e-27;

inline double OmegaEvFromLambdaNm(double lambda_nm) { return kHcEvNm / lambda_nm; }
inline double LambdaNmFromOmegaEv(double omega_ev) { return kHcEvNm / omega_ev; }
inline double TauFsFromGammaEv(double gamma_ev) { return kHbarEvFs / gamma_ev; }
inline double GammaEvFromTauFs(double tau_fs) { return kHbarEvFs / tau_fs; }

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_UNITS_H_
