// The energy bookkeeping at dt and dt/2 (see the header).

#include <sluice/core/result_line.h>
#include <sluice/dem/dem_system.h>
#include <sluice/dem/energy_balance.h>
#include <sluice/dem/energy_balance_validation.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>

namespace sluice
{
  namespace
  {
    struct Run
    {
      EnergyBalance::Totals totals;
      double                triangle_sum = 0., type_sum = 0., ledger_wall_work = 0.;
      double                dt = 0.;
      unsigned long long    steps = 0;
    };

    double sum(const std::vector<double> &v)
    {
      double s = 0.;
      for (const double x : v)
        s += x;
      return s;
    }

    Run run(const SceneParameters &p, MPI_Comm comm)
    {
      DemSystem dem(p, comm);
      unsigned int n_triangles = 0;
      for (const MeshWall &m : dem.walls.meshes())
        n_triangles += m.mesh().size();
      ContactObserver observer(dem.walls.n_walls(), n_triangles, p.n_materials());
      dem.observe(&observer);
      EnergyBalance balance(p.gravity);
      Run           r;
      r.dt    = dem.dt;
      r.steps = static_cast<unsigned long long>(std::ceil(p.end_time / dem.dt - 1e-9));
      const GravityKick kick{p.gravity};
      for (unsigned long long s = 0; s < r.steps; ++s)
        {
          dem.advance(kick);
          observer.take_impacts();
          balance.after_step(dem.particles, observer, dem.dt);
        }
      r.totals           = balance.totals(dem.particles, observer, comm);
      r.triangle_sum     = sum(observer.triangle_shear_work);
      r.type_sum         = sum(observer.ledger.wall_tangential_work_by_type);
      r.ledger_wall_work = observer.ledger.tangential_work[1];
      return r;
    }
  } // namespace

  int run_energy_balance_validation(const SceneParameters &p, MPI_Comm comm)
  {
    const auto start = std::chrono::steady_clock::now();
    int        n_ranks;
    MPI_Comm_size(comm, &n_ranks);
    if (n_ranks > 1)
      throw InputError("error in '" + p.file_name + "': 'validation/case = energy_balance' "
                       "runs on one MPI rank (the bookkeeping is exact there)");
    if (p.automatic_time_step)
      throw InputError("error in '" + p.file_name + "': 'validation/case = energy_balance' "
                       "halves 'simulation/time step', which must then be a number");
    SceneParameters half = p;
    half.time_step       = 0.5 * p.time_step;
    const Run coarse     = run(p, comm);
    const Run fine       = run(half, comm);
    const double order = std::log2(std::abs(coarse.totals.residual / fine.totals.residual));
    const double error = std::abs(coarse.totals.residual / coarse.totals.dissipated);
    // (Relative to the ledger's, or absolute where there is no friction.)
    const double scale       = std::max(std::abs(coarse.ledger_wall_work), 1e-300);
    const double by_triangle = std::abs(coarse.triangle_sum - coarse.ledger_wall_work) / scale;
    const double by_type     = std::abs(coarse.type_sum - coarse.ledger_wall_work) / scale;
    const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "Sluice DEM - energy balance at dt and dt/2 - scene " << p.file_name << "\n";
    for (const Run *r : {&coarse, &fine})
      std::cout << std::setprecision(4) << "dt=" << r->dt << " steps=" << r->steps << " "
                << EnergyBalance::line(r->totals) << "\n";
    std::cout << std::setprecision(3) << "check: residual_order=" << order
              << " (expected 2) wall_tangential_work_by_triangle_difference=" << by_triangle
              << " by_type_difference=" << by_type << "\n";
    write_result_line(std::cout, "energy_balance", error, 0., error, wall_s);
    const bool ok = order > 1.8 && by_triangle < 1e-12 && by_type < 1e-12;
    if (!ok)
      std::cerr << "sluice: validation: the residual must fall as dt^2 and the per-triangle "
                   "and per-type sums equal the ledger's\n";
    if (!ok || (p.validation_tolerance > 0. && error > p.validation_tolerance))
      return 3;
    return 0;
  }
} // namespace sluice
