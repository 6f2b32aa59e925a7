// A fluidized binary mixture: the mass-weighted mean height of each species
// (Gao & Sun, Eq. 46) against time, and Goldschmidt's segregation index,
// which is 0 for a perfectly mixed bed and 1 for a perfectly segregated one.
//
// The species are the particles' material types; the 'small' species is the
// one of the smaller mass-weighted mean radius. With S = <h_small> / <h_large>
// the index is s = (S - 1) / (S_max - 1) (Goldschmidt, Link, Mellema &
// Kuipers, Powder Technol. 138 (2003) 135), where S_max is S of the same bed
// fully segregated: the large species (mass fraction x_L) in the bottom x_L of
// a uniform bed of height H, the small one above it, so that <h_large> =
// x_L H / 2, <h_small> = (1 + x_L) H / 2 and S_max = (1 + x_L) / x_L,
// whatever H. Heights are measured upwards (against gravity) from the bottom
// of the bed, the lowest point of any particle (the distributor, for a bed
// resting on it): measured from below the bed, both heights would carry the
// same offset and S would be biased towards 1.

#include <sluice/coupling/coupling_probe.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The two species' mass, mean height and mean radius at one instant.
    struct SpeciesHeights
    {
      unsigned int small_type = 0, large_type = 0;
      double       mass_small = 0., mass_large = 0.;
      double       height_small = 0., height_large = 0.; // Eq. 46
      double       radius_small = 0., radius_large = 0.;

      double large_fraction() const { return mass_large / (mass_small + mass_large); }
      double ratio() const { return height_small / height_large; }
      double maximum_ratio() const { return (1. + large_fraction()) / large_fraction(); }
      double index() const { return (ratio() - 1.) / (maximum_ratio() - 1.); }
    };

    /// Sums of m, m h and m r per material type over all ranks; refuses a
    /// bed that does not hold exactly two species.
    SpeciesHeights species_heights(const ProbeView &view)
    {
      const SceneParameters &p  = view.p;
      const ParticleStorage &P  = view.dem.particles;
      const Vec3             up = (-1. / norm(p.gravity)) * p.gravity;
      const unsigned int     n_types = p.n_materials();
      const auto             height = [&](unsigned int i) { return dot(P.position[i], up); };
      double                 bottom = std::numeric_limits<double>::max();
      for (unsigned int i = 0; i < P.n_local; ++i)
        bottom = std::min(bottom, height(i) - P.radius[i]);
      MPI_Allreduce(MPI_IN_PLACE, &bottom, 1, MPI_DOUBLE, MPI_MIN, view.comm);
      std::vector<double> sums(3 * n_types, 0.);
      for (unsigned int i = 0; i < P.n_local; ++i)
        {
          double *s = &sums[3 * P.type[i]];
          s[0] += P.mass[i];
          s[1] += P.mass[i] * (height(i) - bottom);
          s[2] += P.mass[i] * P.radius[i];
        }
      MPI_Allreduce(MPI_IN_PLACE, sums.data(), sums.size(), MPI_DOUBLE, MPI_SUM, view.comm);
      std::vector<unsigned int> present;
      for (unsigned int t = 0; t < n_types; ++t)
        if (sums[3 * t] > 0.)
          present.push_back(t);
      if (present.size() != 2)
        throw InputError("error in '" + p.file_name + "': entry 'cfd-dem validation/case' = "
                         "segregation needs particles of exactly two material types (the two "
                         "species, e.g. from 'insertion/size classes'); the bed has " +
                         std::to_string(present.size()));
      std::array<unsigned int, 2> by_size{{present[0], present[1]}};
      const auto mean_radius = [&](unsigned int t) { return sums[3 * t + 2] / sums[3 * t]; };
      if (mean_radius(by_size[1]) < mean_radius(by_size[0]))
        std::swap(by_size[0], by_size[1]);
      SpeciesHeights h;
      h.small_type   = by_size[0];
      h.large_type   = by_size[1];
      h.mass_small   = sums[3 * h.small_type];
      h.mass_large   = sums[3 * h.large_type];
      h.height_small = sums[3 * h.small_type + 1] / h.mass_small;
      h.height_large = sums[3 * h.large_type + 1] / h.mass_large;
      h.radius_small = mean_radius(h.small_type);
      h.radius_large = mean_radius(h.large_type);
      return h;
    }

    class SegregationProbe : public CouplingProbe
    {
    public:
      bool writes_files() const override { return true; } // segregation.csv

      /// Refuses a bed without gravity (no height to measure) or without two
      /// species before the fluid's start.
      void prepare(ProbeView &view) override
      {
        if (!(norm(view.p.gravity) > 0.))
          throw InputError("error in '" + view.p.file_name +
                           "': entry 'cfd-dem validation/case' = segregation measures heights "
                           "against gravity, and 'simulation/gravity' is zero");
        species_heights(view);
      }

      /// The mixed start is the series' first row.
      void start(ProbeView &view) override { record(0., species_heights(view), view); }

      /// A row of the series at the first fluid step at or after every
      /// millisecond: a cadence that does not depend on the end time, so that
      /// a run stopped, restarted and continued to a later end keeps its rows.
      void observe(const double time, ProbeView &view) override
      {
        if (time >= rows.size() * row_interval - 1e-9 * row_interval)
          record(time, species_heights(view), view);
      }

      /// The index averaged over the rows of the second half of the run.
      ProbeResult finish(ProbeView &view) override
      {
        const SpeciesHeights h = species_heights(view);
        double               n = 0., sum = 0., sum_2 = 0.;
        for (const auto &row : rows)
          if (row[0] >= 0.5 * view.p.end_time)
            n += 1., sum += row[3], sum_2 += row[3] * row[3];
        const double mean   = n > 0. ? sum / n : h.index();
        const double spread = n > 0. ? std::sqrt(std::max(0., sum_2 / n - mean * mean)) : 0.;
        ProbeResult  r;
        r.name      = "segregation_index";
        r.value     = mean;
        r.reference = 0.; // Goldschmidt et al. found the bed mixed above U_mf of the large beads
        r.error     = std::abs(r.value);
        std::ostringstream check;
        check.precision(view.p.summary_precision);
        check << "check: segregation small_type=" << h.small_type
              << " large_type=" << h.large_type << " large_mass_fraction=" << h.large_fraction()
              << " mean_height_small=" << h.height_small
              << " mean_height_large=" << h.height_large << " S=" << h.ratio()
              << " S_max=" << h.maximum_ratio() << " index_at_end=" << h.index()
              << " index_at_start=" << (rows.empty() ? 0. : rows[0][3])
              << " index_spread_second_half=" << spread << " rows=" << rows.size()
              << " (segregation.csv)";
        r.checks.push_back(check.str());
        return r;
      }

      /// The series' rows (time, <h_small>, <h_large>, index).
      std::vector<double> state() const override
      {
        std::vector<double> s;
        for (const auto &row : rows)
          s.insert(s.end(), row.begin(), row.end());
        return s;
      }
      void set_state(const std::vector<double> &s) override
      {
        rows.clear();
        for (std::size_t k = 0; k + 3 < s.size(); k += 4)
          rows.push_back({{s[k], s[k + 1], s[k + 2], s[k + 3]}});
      }

    private:
      static constexpr double row_interval = 1e-3; // [s]

      /// A row of the series, kept for the checkpoint and appended to the
      /// CSV file (rank 0) so that a run stopped early leaves its rows; the
      /// first row after the start or a restart writes the file afresh.
      void record(const double time, const SpeciesHeights &h, const ProbeView &view)
      {
        rows.push_back({{time, h.height_small, h.height_large, h.index()}});
        int rank = 0;
        MPI_Comm_rank(view.comm, &rank);
        if (rank != 0 || view.output_directory.empty())
          return;
        const std::string path = view.output_directory + "/segregation.csv";
        std::ofstream     out(path, file_started ? std::ios::app : std::ios::trunc);
        out.precision(10);
        if (!file_started)
          out << "# Gao & Sun Eq. 46: mass-weighted mean height [m] above the bed's bottom (the "
                 "lowest point of any particle) of the small (type "
              << h.small_type << ", mean radius " << h.radius_small << " m) and large (type "
              << h.large_type << ", mean radius " << h.radius_large
              << " m) species; index = (S - 1) / (S_max - 1), S = h_small / h_large, S_max = "
              << h.maximum_ratio() << "\n"
              << "time,mean_height_small,mean_height_large,segregation_index\n";
        for (std::size_t k = file_started ? rows.size() - 1 : 0; k < rows.size(); ++k)
          out << rows[k][0] << "," << rows[k][1] << "," << rows[k][2] << "," << rows[k][3]
              << "\n";
        file_started = true;
      }

      bool                               file_started = false;
      std::vector<std::array<double, 4>> rows;
    };
  } // namespace

  std::unique_ptr<CouplingProbe> make_segregation_probe()
  {
    return std::make_unique<SegregationProbe>();
  }
} // namespace sluice
