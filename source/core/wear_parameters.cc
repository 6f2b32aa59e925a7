// The 'wear and breakage' subsection (see the header).

#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/core/wear_parameters.h>

#include <cmath>
#include <sstream>

namespace sluice
{
  using namespace dealii;

  void declare_wear_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("wear and breakage");
    declare(prm, "collect", "false", Patterns::Bool(),
            "Record the normal impact energy of every contact as it starts and the shear "
            "(friction) work at mesh walls: wear per mesh triangle, impact spectra and "
            "breakage probabilities per particle type. A scene that does not pays nothing.");
    declare(prm, "energy balance", "false", Patterns::Bool(),
            "Book the contacts' energy from the start time on and print at the end the work "
            "of gravity and the walls, the change of kinetic and spring energy, and the "
            "energy dissipated by normal damping, friction and rolling resistance, "
            "particle-particle and particle-wall, with the residual (doc/geometry.md; exact "
            "on one rank).");
    declare(prm, "start time", "0", Patterns::Double(0.),
            "[s] Collection starts here (e.g. once the scene is steady).");
    declare(prm, "wear model", "shear_energy", Patterns::Selection("shear_energy|archard"),
            "shear_energy: depth dh = sum_i C_wr,i E_sh,i / A over the particle types i "
            "(Gao & Sun Eq. 12); archard: dh = k sum F_n s / (H A), s the slip distance.");
    declare(prm, "wear coefficient", "1e-12", Patterns::Double(0.),
            "[m^3/J] C_wr of every particle type on every wall material not listed in "
            "'wear coefficients'.");
    declare(prm, "wear coefficients", "", Patterns::Anything(),
            "[m^3/J] C_wr for given pairs, 'type, material, C; ...'.",
            "empty, or ';'-separated groups of two material types and a number >= 0");
    declare(prm, "archard coefficient", "1e-4", Patterns::Double(0.),
            "[-] Archard's wear coefficient k.");
    declare(prm, "hardness", "1e9", Patterns::Double(0.),
            "[Pa] Hardness H of the walls for Archard's law.", "(0, inf)");
    declare(prm, "breakage coefficients", "", Patterns::Anything(),
            "[kg/J] C_br per particle material type, 'C0, C1, ...' (Gao & Sun Eq. 13: "
            "Br = C_br E_imp / m); empty: 0 for all.",
            "empty, or one number >= 0 per material type");
    declare(prm, "spectrum bins", "30", Patterns::Integer(1, 1000),
            "[-] Log-spaced bins of the impact energy spectrum.");
    declare(prm, "spectrum minimum", "1e-6", Patterns::Double(0.),
            "[J/kg] Lower edge of the spectrum's first bin (impact energy per unit mass).",
            "(0, inf)");
    declare(prm, "spectrum maximum", "100", Patterns::Double(0.),
            "[J/kg] Upper edge of its last bin (larger impacts count in the last bin, smaller "
            "in the first).",
            "above 'spectrum minimum'");
    prm.leave_subsection();
  }

  WearParameters read_wear_parameters(ParameterHandler &prm, const std::string &scene,
                                      const unsigned int n_materials)
  {
    WearParameters w;
    const auto     fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + scene + "': entry 'wear and breakage/" + entry + "' " +
                       what);
    };
    const auto number = [&](const std::string &entry, const std::string &text) {
      std::istringstream in(text);
      double             v;
      std::string        rest;
      if (!(in >> v) || (in >> rest) || !(v >= 0.))
        fail(entry, "has '" + text + "', which is not a number >= 0");
      return v;
    };
    const auto material = [&](const std::string &entry, const std::string &text) {
      const double m = number(entry, text);
      if (m != std::floor(m) || m >= n_materials)
        fail(entry, "has '" + text + "'; allowed: material types 0.." +
                      std::to_string(n_materials - 1));
      return static_cast<unsigned int>(m);
    };
    prm.enter_subsection("wear and breakage");
    w.collect          = prm.get_bool("collect");
    w.energy           = prm.get_bool("energy balance");
    w.start_time       = prm.get_double("start time");
    w.model            = prm.get("wear model") == "archard" ? WearModel::archard :
                                                              WearModel::shear_energy;
    w.wear_coefficient = prm.get_double("wear coefficient");
    for (const auto &group : Utilities::split_string_list(prm.get("wear coefficients"), ';'))
      {
        const auto f = Utilities::split_string_list(group, ',');
        if (f.size() != 3)
          fail("wear coefficients", "has '" + group + "'; expected 'type, material, C'");
        w.wear_coefficient_pairs.push_back({material("wear coefficients", f[0]),
                                            material("wear coefficients", f[1]),
                                            number("wear coefficients", f[2])});
      }
    w.archard_coefficient = prm.get_double("archard coefficient");
    w.hardness            = prm.get_double("hardness");
    if (!(w.hardness > 0.))
      fail("hardness", "= 0 is outside the allowed range (0, inf)");
    for (const auto &c : Utilities::split_string_list(prm.get("breakage coefficients"), ','))
      w.breakage_coefficients.push_back(number("breakage coefficients", c));
    if (!w.breakage_coefficients.empty() && w.breakage_coefficients.size() != n_materials)
      fail("breakage coefficients", "has " + std::to_string(w.breakage_coefficients.size()) +
                                      " numbers for " + std::to_string(n_materials) +
                                      " material types; give one per type");
    w.spectrum_bins    = prm.get_integer("spectrum bins");
    w.spectrum_minimum = prm.get_double("spectrum minimum");
    w.spectrum_maximum = prm.get_double("spectrum maximum");
    if (!(w.spectrum_minimum > 0.) || !(w.spectrum_maximum > w.spectrum_minimum))
      fail("spectrum maximum", "must be above 'spectrum minimum' > 0");
    prm.leave_subsection();
    return w;
  }
} // namespace sluice
