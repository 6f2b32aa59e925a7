// Wear and breakage statistics of a DEM scene (see the header).

#include <sluice/dem/wear_and_breakage.h>

#include <algorithm>
#include <fstream>
#include <iomanip>

namespace sluice
{
  namespace
  {
    const char *energy_field = "impact_energy";
  }

  void WearAndBreakage::declare_fields(const SceneParameters &p, ParticleFieldRegistry &fields)
  {
    if (p.wear.collect || p.wear.energy)
      fields.declare(energy_field, 1, {true, true, true});
  }

  WearAndBreakage::WearAndBreakage(const SceneParameters &p, DemSystem &dem)
    : parameters(p.wear), balance(p.gravity)
  {
    if (!parameters.collect && !parameters.energy)
      return;
    unsigned int n_triangles = 0;
    for (const MeshWall &m : dem.walls.meshes())
      n_triangles += m.mesh().size();
    observer_ = std::make_unique<ContactObserver>(dem.walls.n_walls(), n_triangles,
                                                  p.n_materials());
    impacts   = std::make_unique<ImpactStatistics>(parameters, p.n_materials(),
                                                 dem.fields.find(energy_field)->offset);
    dem.observe(observer_.get());
    balance.count_bodies(dem.clumps.get());
  }

  void WearAndBreakage::attach_when_due(DemSystem &dem)
  {
    if (!active())
      return;
    const bool due = dem.time() >= parameters.start_time - 0.5 * dem.dt;
    if (due != (dem.observer() != nullptr))
      dem.observe(due ? observer_.get() : nullptr);
  }

  void WearAndBreakage::after_step(DemSystem &dem)
  {
    if (!active() || !dem.observer())
      return;
    impacts->take(*observer_, dem.handler_particles(),
                  dem.clumps ? &dem.clumps->member_body() : nullptr);
    if (parameters.energy)
      balance.after_step(dem.handler_particles(), *observer_, dem.dt);
  }

  void WearAndBreakage::open_csv(const std::string &directory, const std::string &base_name,
                                 const bool restart, const double time, MPI_Comm comm)
  {
    if (!active())
      return;
    int rank;
    MPI_Comm_rank(comm, &rank);
    csv.open(directory + "/" + base_name + "_impacts.csv",
             "time,type,particles,impacts_particle,impacts_wall,impact_energy_particle,"
             "impact_energy_wall,mean_impact_energy,mean_breakage_probability,"
             "max_breakage_probability,fraction_broken",
             rank == 0, restart, time);
  }

  void WearAndBreakage::write_rows(const double time, const ParticleStorage &P, MPI_Comm comm)
  {
    if (!active())
      return;
    const auto summary = impacts->summarise(P, comm);
    if (!csv.is_open())
      return;
    for (unsigned int t = 0; t < summary.size(); ++t)
      {
        const auto &s = summary[t];
        csv.row() << time << ',' << t << ',' << s.particles << ',' << s.impacts_particle << ','
                  << s.impacts_wall << ',' << s.energy_particle << ',' << s.energy_wall << ','
                  << s.mean_energy << ',' << s.mean_breakage << ',' << s.max_breakage << ','
                  << s.fraction_broken;
        csv.end_row();
      }
  }

  std::vector<std::vector<TriangleField>> WearAndBreakage::mesh_fields(const WallSet &walls,
                                                                       MPI_Comm comm) const
  {
    std::vector<std::vector<TriangleField>> fields(walls.n_meshes());
    if (!active())
      return fields;
    std::vector<double> impact(observer_->triangle_impact_energy),
      shear(observer_->triangle_shear_work), load_slip(observer_->triangle_load_slip);
    for (auto *a : {&impact, &shear, &load_slip})
      MPI_Allreduce(MPI_IN_PLACE, a->data(), a->size(), MPI_DOUBLE, MPI_SUM, comm);
    const std::size_t n_all   = impact.size();
    const std::size_t n_types = n_all > 0 ? shear.size() / n_all : 0;
    for (unsigned int m = 0; m < walls.n_meshes(); ++m)
      {
        const MeshWall    &wall  = walls.meshes()[m];
        const unsigned int first = walls.triangle_offset(m), n = wall.mesh().size();
        std::vector<double> E_imp(n), E_sh(n, 0.), depth(n, 0.);
        for (unsigned int t = 0; t < n; ++t)
          {
            E_imp[t] = impact[first + t];
            for (std::size_t type = 0; type < n_types; ++type)
              {
                const double w = shear[type * n_all + first + t];
                E_sh[t] += w;
                // Gao & Sun Eq. 12, or Archard: V = k F_n s / H.
                depth[t] += parameters.model == WearModel::archard ?
                              parameters.archard_coefficient * load_slip[type * n_all + first + t] /
                                parameters.hardness :
                              parameters.wear_coefficient_of(type, wall.material()) * w;
              }
            depth[t] /= wall.mesh().areas[t];
          }
        fields[m] = {{"impact_energy", E_imp}, {"shear_energy", E_sh}, {"wear_depth", depth}};
      }
    return fields;
  }

  void WearAndBreakage::finish(std::ostream &out, const DemSystem &dem,
                               const std::string &directory, const std::string &base_name)
  {
    if (!active())
      return;
    if (parameters.energy)
      {
        const EnergyBalance::Totals t =
          balance.totals(dem.handler_particles(), *observer_, dem.comm);
        if (dem.rank == 0)
          out << EnergyBalance::line(t) << "\n";
      }
    if (!parameters.collect)
      return;
    const auto fields  = mesh_fields(dem.walls, dem.comm);
    const auto summary = impacts->summarise(dem.handler_particles(), dem.comm);
    impacts->write_spectrum(directory + "/" + base_name + "_spectrum.csv", dem.comm);
    if (dem.rank != 0)
      return;
    for (unsigned int m = 0; m < fields.size(); ++m)
      {
        const TriangleMesh        &mesh  = dem.walls.meshes()[m].mesh();
        const std::vector<double> &depth = fields[m][2].second;
        double                     E_imp = 0., E_sh = 0., volume = 0.;
        for (unsigned int t = 0; t < mesh.size(); ++t)
          {
            E_imp += fields[m][0].second[t];
            E_sh += fields[m][1].second[t];
            volume += depth[t] * mesh.areas[t];
          }
        const unsigned int deepest =
          std::max_element(depth.begin(), depth.end()) - depth.begin();
        const auto &v = mesh.triangles[deepest];
        const Vec3  c = (1. / 3.) * (mesh.vertices[v[0]] + mesh.vertices[v[1]] + mesh.vertices[v[2]]);
        out << "wear: mesh=" << dem.walls.meshes()[m].name() << " impact_energy=" << E_imp
            << " shear_energy=" << E_sh << " worn_volume=" << volume
            << " max_depth=" << depth[deepest] << " at=(" << c.x << ", " << c.y << ", " << c.z
            << ")\n";
      }
    for (unsigned int t = 0; t < summary.size(); ++t)
      {
        const auto &s = summary[t];
        out << "breakage: type=" << t << " particles=" << s.particles
            << " impacts_particle=" << s.impacts_particle << " impacts_wall=" << s.impacts_wall
            << " mean_impact_energy=" << s.mean_energy << " mean_breakage=" << s.mean_breakage
            << " max_breakage=" << s.max_breakage << " fraction_broken=" << s.fraction_broken
            << "\n";
      }
    out << "output: " << directory << "/" << base_name << "_spectrum.csv\n";
  }

  std::vector<double> WearAndBreakage::state(MPI_Comm comm) const
  {
    if (!active())
      return {};
    std::vector<double> s = impacts->state();
    const std::vector<double> b = balance.state();
    s.insert(s.end(), b.begin(), b.end());
    // (The balance's baseline length is the same on every rank; its sum is kept.)
    const double length = b.size() > 1 ? b[1] : 0.;
    MPI_Allreduce(MPI_IN_PLACE, s.data(), s.size(), MPI_DOUBLE, MPI_SUM, comm);
    if (b.size() > 1)
      s[impacts->state().size() + 1] = length;
    return s;
  }

  bool WearAndBreakage::set_state(const std::vector<double> &numbers, MPI_Comm comm)
  {
    if (!active() || numbers.empty())
      return true;
    int rank;
    MPI_Comm_rank(comm, &rank);
    const std::size_t   n = impacts->state().size();
    if (numbers.size() < n)
      return false;
    std::vector<double> b(numbers.begin() + n, numbers.end());
    if (rank != 0)
      for (std::size_t k = 0; k < b.size(); ++k)
        if (k != 1)
          b[k] = 0.;
    balance.set_state(b);
    const std::vector<double> mine(numbers.begin(), numbers.begin() + n);
    return impacts->set_state(rank == 0 ? mine : std::vector<double>(n, 0.));
  }
} // namespace sluice
