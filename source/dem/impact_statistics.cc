// Impact energies per particle and per type (see the header).

#include <sluice/core/output_files.h>
#include <sluice/dem/impact_statistics.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace sluice
{
  ImpactStatistics::ImpactStatistics(const WearParameters &p, const unsigned int n_types,
                                     const unsigned int energy_offset)
    : parameters(p), n_types(n_types), energy_offset(energy_offset), counts(2 * n_types, 0.),
      energies(2 * n_types, 0.), histogram(2 * n_types * p.spectrum_bins, 0.)
  {}

  unsigned int ImpactStatistics::bin_of(const double e) const
  {
    const double lo = std::log(parameters.spectrum_minimum),
                 hi = std::log(parameters.spectrum_maximum);
    const double s  = e > 0. ? (std::log(e) - lo) / (hi - lo) : 0.;
    return std::min<unsigned int>(parameters.spectrum_bins - 1,
                                  static_cast<unsigned int>(std::max(0., s) *
                                                            parameters.spectrum_bins));
  }

  void ImpactStatistics::take(ContactObserver &observer, ParticleStorage &P,
                              const std::vector<unsigned int> *member_body)
  {
    for (const ImpactRecord &r : observer.take_impacts())
      {
        const unsigned int i = member_body ? (*member_body)[r.index] : r.index;
        P.extra_of(i)[energy_offset] += r.energy;
        const std::size_t k = at(r.type, r.wall);
        counts[k] += 1.;
        energies[k] += r.energy;
        histogram[k * parameters.spectrum_bins + bin_of(r.energy / P.mass[i])] += 1.;
      }
  }

  std::vector<ImpactStatistics::TypeSummary>
  ImpactStatistics::summarise(const ParticleStorage &P, MPI_Comm comm) const
  {
    // Per type: the sums, then the largest Br.
    constexpr unsigned int n_sums = 8;
    std::vector<double>    sums(n_sums * n_types, 0.), largest(n_types, 0.);
    for (unsigned int t = 0; t < n_types; ++t)
      {
        sums[n_sums * t + 1] = counts[at(t, false)];
        sums[n_sums * t + 2] = counts[at(t, true)];
        sums[n_sums * t + 3] = energies[at(t, false)];
        sums[n_sums * t + 4] = energies[at(t, true)];
      }
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        const unsigned int t = P.type[i];
        const double       E = P.extra_of(i)[energy_offset];
        const double       C =
          parameters.breakage_coefficients.empty() ? 0. : parameters.breakage_coefficients[t];
        const double Br = C * E / P.mass[i];
        sums[n_sums * t] += 1.;
        sums[n_sums * t + 5] += E;
        sums[n_sums * t + 6] += Br;
        sums[n_sums * t + 7] += Br >= 1. ? 1. : 0.;
        largest[t] = std::max(largest[t], Br);
      }
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM, comm);
    MPI_Allreduce(MPI_IN_PLACE, largest.data(), largest.size(), MPI_DOUBLE, MPI_MAX, comm);
    std::vector<TypeSummary> out(n_types);
    for (unsigned int t = 0; t < n_types; ++t)
      {
        const double *s = &sums[n_sums * t];
        const double  n = std::max(s[0], 1.);
        out[t]          = {s[0],     s[1],     s[2],     s[3],       s[4],
                           s[5] / n, s[6] / n, largest[t], s[7] / n};
      }
    return out;
  }

  void ImpactStatistics::write_spectrum(const std::string &path, MPI_Comm comm) const
  {
    std::vector<double> all(histogram);
    MPI_Allreduce(MPI_IN_PLACE, all.data(), all.size(), MPI_DOUBLE, MPI_SUM, comm);
    int rank;
    MPI_Comm_rank(comm, &rank);
    if (rank != 0)
      return;
    const unsigned int n  = parameters.spectrum_bins;
    const double       lo = std::log10(parameters.spectrum_minimum),
                 width    = (std::log10(parameters.spectrum_maximum) - lo) / n;
    std::ostringstream out;
    out << "type,kind,energy_per_mass_low,energy_per_mass_high,impacts,impacts_per_decade\n"
        << std::setprecision(10);
    for (unsigned int t = 0; t < n_types; ++t)
      for (const bool wall : {false, true})
        for (unsigned int b = 0; b < n; ++b)
          out << t << ',' << (wall ? "wall" : "particle") << ','
              << std::pow(10., lo + b * width) << ',' << std::pow(10., lo + (b + 1) * width)
              << ',' << all[at(t, wall) * n + b] << ',' << all[at(t, wall) * n + b] / width
              << '\n';
    write_file_atomically(path, out.str());
  }

  std::vector<double> ImpactStatistics::state() const
  {
    std::vector<double> s(counts);
    s.insert(s.end(), energies.begin(), energies.end());
    s.insert(s.end(), histogram.begin(), histogram.end());
    return s;
  }

  bool ImpactStatistics::set_state(const std::vector<double> &s)
  {
    if (s.size() != counts.size() + energies.size() + histogram.size())
      return false;
    auto from = s.begin();
    for (auto *a : {&counts, &energies, &histogram})
      {
        std::copy(from, from + a->size(), a->begin());
        from += a->size();
      }
    return true;
  }
} // namespace sluice
