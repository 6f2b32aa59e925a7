// Checkpoint and restart of a time-dependent fluid run. Restart is where coupled
// codes break most often (DESIGN.md §6), so everything BDF2 and the adapted mesh
// depend on is saved: the p4est mesh, u^{n+1}, u^n, u^{n-1}, three porosity
// levels, the momentum-source field, the time, the last two step sizes and the
// step count. tests/fluid/restart_* check that a run continued from a
// checkpoint ends exactly where the uninterrupted run ends.

#include <sluice/core/scene_parameters.h>
#include <sluice/fluid/fluid_mesh.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/distributed/solution_transfer.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    using Transfer = parallel::distributed::SolutionTransfer<3, TrilinosWrappers::MPI::Vector>;

    /// Renames every file whose name starts with 'from' to start with 'to'.
    void rename_prefix(const std::string &from, const std::string &to)
    {
      namespace fs           = std::filesystem;
      const fs::path    dir  = fs::path(from).parent_path().empty() ? fs::path(".") :
                                                                        fs::path(from).parent_path();
      const std::string name = fs::path(from).filename().string();
      for (const auto &entry : fs::directory_iterator(dir))
        {
          const std::string file = entry.path().filename().string();
          if (file.compare(0, name.size(), name) == 0)
            fs::rename(entry.path(), fs::path(to).parent_path() /
                                       (fs::path(to).filename().string() + file.substr(name.size())));
        }
    }
  } // namespace

  void VansSolver::save_checkpoint(const std::string &base,
                                   const std::vector<std::string> &extra) const
  {
    const std::string tmp = base + ".writing";
    Transfer solution_transfer(dof_handler), porosity_transfer(porosity_dof_handler),
      source_transfer(source_dof_handler);
    solution_transfer.prepare_for_serialization(
      std::vector<const TrilinosWrappers::MPI::Vector *>{&present_solution, &old_solutions[0],
                                                         &old_solutions[1]});
    // With the semi-implicit exchange, the drag coefficient the last step
    // applied travels with the porosity: the next step returns its term.
    std::vector<const TrilinosWrappers::MPI::Vector *> scalar_fields{
      &porosity_levels[0], &porosity_levels[1], &porosity_levels[2]};
    if (prm.exchange_drag_as_field)
      scalar_fields.push_back(&applied_exchange_drag);
    porosity_transfer.prepare_for_serialization(scalar_fields);
    if (prm.momentum_source_as_field)
      source_transfer.prepare_for_serialization(momentum_source_field);
    triangulation.save(tmp + ".mesh");

    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ofstream state(tmp + ".state");
        state << std::setprecision(17) << "sluice fluid checkpoint 1\n"
              << "time " << current_time << "\nstep_sizes " << time_steps[0] << ' '
              << time_steps[1] << "\nsteps " << n_steps_done << "\ndofs " << dof_handler.n_dofs()
              << '\n';
        for (const auto &line : extra)
          state << "extra " << line << '\n';
      }
    MPI_Barrier(comm);
    // Only now replace the previous checkpoint.
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      rename_prefix(tmp, base);
    MPI_Barrier(comm);
  }

  std::vector<std::string> VansSolver::load_checkpoint(const std::string &base,
                                                       const std::string &entry)
  {
    std::ifstream state(base + ".state");
    std::string   header;
    if (!state || !std::getline(state, header) || header != "sluice fluid checkpoint 1")
      throw InputError("error in '" + file_name + "': entry '" + entry + "' names '" + base +
                       "', but '" + base + ".state' is not a Sluice fluid checkpoint");
    std::string                     key, line;
    types::global_dof_index         saved_dofs = 0;
    std::vector<std::string>        extra;
    state >> key >> current_time >> key >> time_steps[0] >> time_steps[1] >> key >>
      n_steps_done >> key >> saved_dofs;
    std::getline(state, line);
    while (std::getline(state, line))
      if (line.compare(0, 6, "extra ") == 0)
        extra.push_back(line.substr(6));
    steady = false;

    triangulation.clear(); // (a coupled scene has initialised its fluid)
    make_fluid_mesh(triangulation, prm, file_name, true);
    try
      {
        triangulation.load(base + ".mesh");
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        throw InputError("error in '" + file_name + "': entry '" + entry + "': the mesh in '" +
                         base + ".mesh' does not fit this scene's coarse mesh:\n" +
                         info.str());
      }
    dof_handler.reinit(triangulation);
    porosity_dof_handler.reinit(triangulation);
    source_dof_handler.reinit(triangulation);
    setup_dofs();
    if (dof_handler.n_dofs() != saved_dofs)
      throw InputError("error in '" + file_name + "': entry '" + entry + "': the checkpoint has " +
                       std::to_string(saved_dofs) +
                       " unknowns, this scene's elements give " +
                       std::to_string(dof_handler.n_dofs()) + "; the degrees must not change");

    Transfer solution_transfer(dof_handler), porosity_transfer(porosity_dof_handler),
      source_transfer(source_dof_handler);
    std::vector<TrilinosWrappers::MPI::Vector> u(3, TrilinosWrappers::MPI::Vector(owned, comm));
    std::vector<TrilinosWrappers::MPI::Vector *> u_ptr = {&u[0], &u[1], &u[2]};
    solution_transfer.deserialize(u_ptr);
    present_solution = u[0];
    old_solutions[0] = u[1];
    old_solutions[1] = u[2];
    const unsigned int n_scalar = prm.exchange_drag_as_field ? 4 : 3;
    std::vector<TrilinosWrappers::MPI::Vector> eps(
      n_scalar, TrilinosWrappers::MPI::Vector(porosity_owned, comm));
    std::vector<TrilinosWrappers::MPI::Vector *> eps_ptr;
    for (auto &v : eps)
      eps_ptr.push_back(&v);
    porosity_transfer.deserialize(eps_ptr);
    for (unsigned int l = 0; l < 3; ++l)
      porosity_levels[l] = eps[l];
    if (prm.exchange_drag_as_field)
      applied_exchange_drag = eps[3];
    if (prm.momentum_source_as_field)
      {
        TrilinosWrappers::MPI::Vector source(source_owned, comm);
        source_transfer.deserialize(source);
        momentum_source_field = source;
      }
    return extra;
  }
} // namespace sluice
