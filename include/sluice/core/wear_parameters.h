#pragma once
// The 'wear and breakage' subsection: what a scene collects of the contacts'
// energies for wear (Gao & Sun 2021 Eq. 12, or Archard's law) and breakage
// (Eq. 13), and from when (doc/geometry.md).

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace sluice
{
  enum class WearModel
  {
    shear_energy, // dh = sum_i C_wr,i E_sh,i / A (Gao & Sun Eq. 12)
    archard       // dh = k sum F_n s / (H A)
  };

  struct WearParameters
  {
    bool      collect    = false;
    bool      energy     = false; // print the energy bookkeeping at the end
    double    start_time = 0.; // [s]
    WearModel model      = WearModel::shear_energy;
    // C_wr [m^3/J] per (particle type, wall material): 'default' unless listed.
    double              wear_coefficient = 1e-12;
    struct Pair
    {
      unsigned int type, material;
      double       value;
    };
    std::vector<Pair> wear_coefficient_pairs;
    double            archard_coefficient = 1e-4; // k [-]
    double            hardness            = 1e9;  // H [Pa]
    // C_br [kg/J] per particle type (Br = C_br E_imp / m, Eq. 13); empty: 0.
    std::vector<double> breakage_coefficients;
    unsigned int        spectrum_bins    = 30;
    double              spectrum_minimum = 1e-6; // [J/kg]
    double              spectrum_maximum = 1e2;  // [J/kg]

    /// C_wr of a particle type on a wall material.
    double wear_coefficient_of(const unsigned int type, const unsigned int material) const
    {
      for (const Pair &p : wear_coefficient_pairs)
        if (p.type == type && p.material == material)
          return p.value;
      return wear_coefficient;
    }
  };

  void declare_wear_parameters(dealii::ParameterHandler &prm);

  /// Throws InputError naming the entry.
  WearParameters read_wear_parameters(dealii::ParameterHandler &prm, const std::string &scene,
                                      unsigned int n_materials);
} // namespace sluice
