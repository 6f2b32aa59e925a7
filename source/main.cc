// sluice: runs the scene described by a .prm file.
//
//   sluice scene.prm                 run a scene
//   mpirun -np N sluice scene.prm    the same on N MPI ranks
//   sluice --print-parameters        every entry with default, unit and range
//   sluice --help                    this text

#include <sluice/core/scene_parameters.h>
#include <sluice/coupling/cfd_dem_scene.h>
#include <sluice/coupling/imported_field_scene.h>
#include <sluice/dem/dem_simulation.h>
#include <sluice/fluid/fluid_scene.h>
#include <sluice/fluid/vans_solver.h>
#include <sluice/sph/sph_scene.h>

#include <deal.II/base/mpi.h>

#include <iostream>
#include <string>

namespace
{
  void print_usage(std::ostream &out)
  {
    out << "Sluice - particle-fluid flow (soft-sphere DEM, volume-averaged Navier-Stokes).\n\n"
        << "usage:\n"
        << "  sluice scene.prm                 run the scene\n"
        << "  mpirun -np N sluice scene.prm    run it on N MPI ranks\n"
        << "  sluice --print-parameters        list every .prm entry with its default,\n"
        << "                                   unit [in brackets], range and meaning\n"
        << "  sluice --help                    this text\n\n"
        << "Exit codes: 0 success, 1 usage, 2 bad input (nothing written), 3 a validation\n"
        << "error above 'validation/tolerance', 4 the fluid solver could not go on (the\n"
        << "message names the parameter to change), 5 the particles could not go on (a\n"
        << "non-finite state, an overlap beyond 'simulation/maximum overlap', a particle\n"
        << "too fast for its step; the message names the particle and the step). The\n"
        << "output written before a stop with 4 or 5 stays readable, and every series\n"
        << "the scene writes gets one more entry with the state at the stop (the last\n"
        << "line of the message names them). 6 an output file could not be written\n"
        << "during the run (disk full; the message names it).\n";
  }

  /// The line naming what a stopped scene wrote at the stop, if anything.
  std::string written_at_stop(const sluice::RunStopped &e)
  {
    return e.written_at_stop.empty() ? std::string() : "sluice: " + e.written_at_stop + "\n";
  }
} // namespace

int main(int argc, char **argv)
{
  // One thread per rank: the DEM loop is not threaded, and deal.II's TBB pool
  // would only compete with the other ranks.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  if (argc != 2)
    {
      if (root)
        print_usage(std::cerr);
      return 1;
    }
  const std::string arg = argv[1];
  if (arg == "--help" || arg == "-h")
    {
      if (root)
        print_usage(std::cout);
      return 0;
    }
  if (arg == "--print-parameters")
    {
      if (root)
        sluice::print_scene_parameters(std::cout);
      return 0;
    }

  try
    {
      const sluice::SceneParameters parameters = sluice::read_scene_parameters(arg);
      if (parameters.physics == sluice::Physics::fluid)
        return sluice::run_fluid_scene(parameters, MPI_COMM_WORLD);
      if (parameters.physics == sluice::Physics::cfd_dem)
        return sluice::run_cfd_dem_scene(parameters, MPI_COMM_WORLD);
      if (parameters.physics == sluice::Physics::sph)
        return sluice::run_sph_scene(parameters, MPI_COMM_WORLD);
      if (parameters.imported_field.active())
        return sluice::run_imported_field_scene(parameters, MPI_COMM_WORLD);
      return sluice::run_dem_scene(parameters, MPI_COMM_WORLD);
    }
  catch (const sluice::SolverFailure &e)
    {
      if (root)
        std::cerr << "sluice: the fluid solver stopped: " << e.what() << std::endl
                  << written_at_stop(e);
      return 4;
    }
  catch (const sluice::SimulationFailure &e)
    {
      if (root)
        std::cerr << "sluice: the simulation stopped: " << e.what() << std::endl
                  << written_at_stop(e);
      return 5;
    }
  catch (const sluice::OutputError &e)
    {
      // Only the rank whose write failed knows; the others would wait for it.
      std::cerr << "sluice: output could not be written: " << e.what() << std::endl;
      if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        MPI_Abort(MPI_COMM_WORLD, 6);
      return 6;
    }
  catch (const sluice::InputError &e)
    {
      // Every rank reads the same file and finds the same fault; one reports it.
      if (root)
        std::cerr << "sluice: " << e.what() << std::endl;
      return 2;
    }
}
