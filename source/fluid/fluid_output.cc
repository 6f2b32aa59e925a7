// Snapshots of the fluid for ParaView: velocity (a vector), pressure and
// porosity, one .vtu per rank and a .pvtu record per snapshot.

#include <sluice/core/output_files.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/numerics/data_out.h>

namespace sluice
{
  using namespace dealii;

  std::string VansSolver::write_vtu(const std::string &directory, const std::string &base,
                                    const unsigned int step) const
  {
    std::vector<std::string> names = {"velocity", "velocity", "velocity", "pressure"};
    std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
      3, DataComponentInterpretation::component_is_part_of_vector);
    kinds.push_back(DataComponentInterpretation::component_is_scalar);

    DataOut<3> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(present_solution, names, DataOut<3>::type_dof_data, kinds);
    data_out.add_data_vector(porosity_dof_handler, porosity_levels[0], "porosity");
    Vector<float> subdomain(triangulation.n_active_cells());
    subdomain = triangulation.locally_owned_subdomain();
    data_out.add_data_vector(subdomain, "rank");
    data_out.build_patches(*mapping, prm.velocity_degree, DataOut<3>::curved_inner_cells);
    try
      {
        return data_out.write_vtu_with_pvtu_record(directory + "/", base, step, comm, 5, 0);
      }
    catch (const dealii::ExceptionBase &e)
      {
        throw OutputError("cannot write the fluid snapshot " + std::to_string(step) + " of '" +
                          directory + "/" + base + "': " + e.get_exc_name());
      }
  }
} // namespace sluice
