// The particle-fluid exchange through a ParticleHandler on the fluid mesh (see
// the header). Deposits are made per home cell: the support cells' quadrature
// data are computed once for all particles of the cell, and each support cell
// receives one accumulated local vector per quantity.

#include <sluice/coupling/particle_fluid_exchange.h>
#include <sluice/dem/particle_fields.h>
#include <sluice/fluid/vans_solver.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/particles/particle_handler.h>

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    // Properties of a particle in the fluid-side handler.
    /// What a particle carries on the fluid mesh, declared like the DEM's
    /// per-particle fields (particle_fields.h); all of it travels to the rank
    /// that owns the particle's fluid cell.
    struct FluidSideLayout
    {
      FluidSideLayout()
      {
        const ParticleFieldRegistry::Use travels{true, false, false};
        volume   = registry.declare("volume", 1, travels);
        velocity = registry.declare("velocity", 3, travels);
        force    = registry.declare("reaction_force", 3, travels);
        drag     = registry.declare("drag_coefficient", 1, travels);
        rank     = registry.declare("dem_rank", 1, travels);  // where the sample returns
        index    = registry.declare("dem_index", 1, travels); // and to which particle
      }
      ParticleFieldRegistry registry;
      unsigned int          volume, velocity, force, drag, rank, index;
    };
    const FluidSideLayout layout;
    // One sample sent back: index, then the FluidSample fields.
    constexpr unsigned int sample_stride = 23;

    /// K(xi) = (1 - xi^2)^4 for xi < 1 (Gao & Sun Eq. 24), unnormalised.
    double kernel(const double xi)
    {
      if (xi >= 1.)
        return 0.;
      const double a = 1. - xi * xi;
      return a * a * a * a;
    }

    /// The squared distance from p to the box (0 inside).
    double box_distance_square(const BoundingBox<3> &box, const Point<3> &p)
    {
      const auto &[lower, upper] = box.get_boundary_points();
      double      s              = 0.;
      for (unsigned int d = 0; d < 3; ++d)
        {
          const double gap = std::max({lower[d] - p[d], 0., p[d] - upper[d]});
          s += gap * gap;
        }
      return s;
    }
  } // namespace

  struct ParticleFluidExchange::Implementation
  {
    const DoFHandler<3>          &dofs;
    const Mapping<3>             &mapping;
    ProjectionScheme              scheme;
    double                        radius;
    std::unique_ptr<Particles::ParticleHandler<3>> handler;
    // The handler (with the point-location cache it builds) and every rank's
    // boxes serve until the mesh changes; gather() then starts them again.
    std::vector<std::vector<BoundingBox<3>>> global_boxes;
    bool                          handler_current = false;
    std::size_t                   n_given = 0; // particles passed to the last gather()
    std::vector<std::array<unsigned int, 3>> periodic_pairs;

    /// A periodic image of a vertex: the vertex on the far side, and how many
    /// periods (per periodic pair) lie between the two.
    struct Image
    {
      unsigned int        vertex;
      std::array<int, 3>  periods;
    };

    /// For every vertex on a periodic face, its images across the periodic
    /// pairs (all combinations: a corner of two periodic pairs has three), and
    /// the translation of each pair.
    std::vector<std::vector<Image>> periodic_images(std::vector<Tensor<1, 3>> &translations) const;

    // What the kernel deposit needs from the mesh, built once per mesh: the
    // cells at each vertex, the vertices' periodic images, the smallest cell.
    // The triangulation's any_change signal (refinement, repartitioning) marks
    // it stale.
    struct MeshData
    {
      bool                                                         current = false;
      std::vector<std::set<Triangulation<3>::active_cell_iterator>> vertex_to_cells;
      std::vector<std::vector<Image>>                              images;
      std::vector<Tensor<1, 3>>                                    translations;
      double                                                       smallest_cell = 0.;
      // The scalar field's dofs and their hanging and periodic constraints.
      IndexSet                                                     relevant;
      AffineConstraints<double>                                    hanging;
      // Diffusion smoothing (Sun & Xiao 2015): M_L + tau K and its step count.
      std::unique_ptr<TrilinosWrappers::SparseMatrix>              smoothing_matrix;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG>           smoothing_preconditioner;
      unsigned int                                                 smoothing_steps = 0;
    };
    double                       bandwidth = 0.; // [m], 0: no smoothing
    /// m_i = integral of phi_i, the lumped mass of the scalar field.
    void lumped_mass(const AffineConstraints<double> &hanging, const IndexSet &owned,
                     const IndexSet &relevant, FEValues<3> &fe_values,
                     TrilinosWrappers::MPI::Vector &lumped) const;
    /// Diffusion-based coarse graining of every deposited channel (in place).
    void smooth(std::vector<TrilinosWrappers::MPI::Vector> &rhs,
                const TrilinosWrappers::MPI::Vector &lumped,
                const AffineConstraints<double> &hanging, const IndexSet &owned,
                const IndexSet &relevant) const;
    /// The integral of the projected solid fraction, by quadrature.
    double field_integral(const TrilinosWrappers::MPI::Vector &solid_fraction,
                          const IndexSet &owned, const IndexSet &relevant,
                          FEValues<3> &fe_values) const;

    // ---- The deposit, in parts (project() runs them in order) ----
    /// Which quantities are deposited ("channels"): volume, then V_p v_p
    /// (with velocity), then F_p (with force), then k_p (with drag).
    /// Volume, V_p v_p, F_p and k_p: at most 1 + 3 + 3 + 1 channels.
    static constexpr unsigned int max_channels = 8;
    struct Channels
    {
      bool         with_velocity = false, with_force = false, with_drag = false;
      unsigned int first_velocity = 1, first_force = 1, first_drag = 1, n = 1;
    };
    /// The particles' own sums, for the conservation record.
    struct ParticleSums
    {
      double       volume = 0., drag = 0.;
      Tensor<1, 3> momentum, force;
    };
    /// Every particle's channels into rhs, with the kernel or at the centroid.
    ParticleSums deposit(const Channels &channels, const AffineConstraints<double> &hanging,
                         FEValues<3> &fe_values,
                         std::vector<TrilinosWrappers::MPI::Vector> &rhs) const;
    /// A cell of a kernel's support: its quadrature data and the local
    /// right-hand sides, one per channel.
    struct SupportCell
    {
      DoFHandler<3>::active_cell_iterator cell;
      bool                                is_home = false;
      std::vector<Point<3>>               x; // shifted next to the home cell
      BoundingBox<3>                      box; // around x
      std::vector<double>                 JxW;
      FullMatrix<double>                  shape; // [q][i]
      // The deposits, [i][channel]: one particle's channels lie side by side.
      std::vector<double> local;
    };
    /// The support of the particles in 'home' (Gao & Sun's kernel reaches the
    /// cells at the home cell's vertices).
    void support_cells(const DoFHandler<3>::active_cell_iterator &home, unsigned int n_channels,
                       FEValues<3> &fe_values, std::vector<SupportCell> &support) const;
    /// One particle at xp (reference point xi in the home cell) deposits
    /// 'value' per channel with the normalised kernel weights.
    void deposit_with_kernel(const Point<3> &xp, const Point<3> &xi,
                             const std::vector<double> &value,
                             std::vector<SupportCell> &support) const;
    mutable std::vector<double>       weights; // scratch of deposit_with_kernel
    mutable std::vector<unsigned int> within;  // ditto: the (cell, point)s the kernel reaches
    /// The nodal solid fraction b_i / m_i capped at max_solid_fraction;
    /// returns how many nodes (all ranks) were capped.
    unsigned int solid_fraction_from(const TrilinosWrappers::MPI::Vector &volume,
                                     const TrilinosWrappers::MPI::Vector &lumped,
                                     const AffineConstraints<double> &hanging,
                                     const IndexSet &owned, double max_solid_fraction,
                                     TrilinosWrappers::MPI::Vector &solid_fraction) const;
    /// The mean solid velocity per component; returns this rank's field momentum.
    Tensor<1, 3> solid_velocity_from(const std::vector<TrilinosWrappers::MPI::Vector> &rhs,
                                     unsigned int first_velocity,
                                     const AffineConstraints<double> &hanging,
                                     const IndexSet &owned,
                                     std::array<TrilinosWrappers::MPI::Vector, 3> &u) const;
    /// The reaction force per volume on the FE_Q^3 dofs; returns this rank's
    /// part of the field's integral.
    Tensor<1, 3> force_density_from(const std::vector<TrilinosWrappers::MPI::Vector> &rhs,
                                    unsigned int first_force,
                                    const TrilinosWrappers::MPI::Vector &lumped,
                                    const AffineConstraints<double> &hanging,
                                    const IndexSet &owned, const IndexSet &relevant,
                                    const DoFHandler<3> &force_dofs,
                                    TrilinosWrappers::MPI::Vector &force_density) const;
    /// The drag coefficient per volume on the scalar dofs; returns this rank's
    /// part of the field's integral.
    double drag_density_from(const TrilinosWrappers::MPI::Vector &deposit,
                             const TrilinosWrappers::MPI::Vector &lumped,
                             const AffineConstraints<double> &hanging, const IndexSet &owned,
                             TrilinosWrappers::MPI::Vector &drag_density) const;

    mutable MeshData             mesh_data;
    boost::signals2::connection  mesh_change, repartition;

    const MeshData &current_mesh_data() const
    {
      if (!mesh_data.current)
        {
          const auto &tria = dofs.get_triangulation();
          double      smallest = std::numeric_limits<double>::max();
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned())
              smallest = std::min(smallest, cell->minimum_vertex_distance());
          mesh_data.smallest_cell   = Utilities::MPI::min(smallest, tria.get_communicator());
          mesh_data.vertex_to_cells = GridTools::vertex_to_cell_map(tria);
          mesh_data.images          = periodic_images(mesh_data.translations);
          mesh_data.relevant.clear();
          DoFTools::extract_locally_relevant_dofs(dofs, mesh_data.relevant);
          mesh_data.hanging.clear();
          mesh_data.hanging.reinit(mesh_data.relevant);
          DoFTools::make_hanging_node_constraints(dofs, mesh_data.hanging);
          for (const auto &pair : periodic_pairs)
            DoFTools::make_periodicity_constraints(dofs, pair[0], pair[1], pair[2],
                                                   mesh_data.hanging);
          mesh_data.hanging.close();
          mesh_data.smoothing_matrix.reset();
          mesh_data.smoothing_preconditioner.reset();
          mesh_data.current         = true;
        }
      return mesh_data;
    }

    Implementation(const DoFHandler<3> &d, const Mapping<3> &m, ProjectionScheme s, double r)
      : dofs(d), mapping(m), scheme(s), radius(r)
    {
      auto &signals = d.get_triangulation().signals; // (a mutable member)
      mesh_change = signals.any_change.connect([this]() {
        mesh_data.current = false;
        handler_current   = false;
      });
      // (New owners: new dof ranges, so the constraints are built again.)
      repartition = signals.post_distributed_repartition.connect([this]() {
        mesh_data.current = false;
        handler_current   = false;
      });
    }
    ~Implementation()
    {
      mesh_change.disconnect();
      repartition.disconnect();
    }
  };

  ParticleFluidExchange::ParticleFluidExchange(const DoFHandler<3> &scalar_dofs,
                                               const Mapping<3>    &mapping,
                                               const ProjectionScheme scheme,
                                               const double           kernel_radius)
    : impl(std::make_unique<Implementation>(scalar_dofs, mapping, scheme, kernel_radius))
  {}

  ParticleFluidExchange::~ParticleFluidExchange() = default;

  void ParticleFluidExchange::set_smoothing_bandwidth(const double b)
  {
    impl->bandwidth = b;
    impl->mesh_data.smoothing_matrix.reset();
  }

  std::vector<std::vector<ParticleFluidExchange::Implementation::Image>>
  ParticleFluidExchange::Implementation::periodic_images(
    std::vector<Tensor<1, 3>> &translations) const
  {
    const auto &tria = dofs.get_triangulation();
    MPI_Comm    comm = tria.get_communicator();
    std::vector<std::vector<Image>> images(tria.n_vertices());
    translations.assign(periodic_pairs.size(), Tensor<1, 3>());
    if (periodic_pairs.empty())
      return images;

    double h_min = std::numeric_limits<double>::max();
    for (const auto &cell : tria.active_cell_iterators())
      if (!cell->is_artificial())
        h_min = std::min(h_min, cell->minimum_vertex_distance());
    h_min            = Utilities::MPI::min(h_min, comm);
    const double tol = 1e-6 * h_min;
    using Key        = std::array<long long, 3>;
    const auto key   = [&](const Point<3> &x) {
      return Key{{std::llround(x[0] / tol), std::llround(x[1] / tol), std::llround(x[2] / tol)}};
    };

    // One step across each pair: a vertex on the first face and the vertex at
    // its translated position on the second (found among the second face's
    // vertices of the owned and ghost cells, which p4est's periodic ghost
    // layer provides).
    std::vector<std::vector<std::pair<unsigned int, std::array<int, 3>>>> step(tria.n_vertices());
    for (unsigned int k = 0; k < periodic_pairs.size(); ++k)
      {
        const auto [first, second, direction] = periodic_pairs[k];
        // The translation: the mean face position of the second boundary
        // minus that of the first, along the pair's direction.
        double sums[4] = {0., 0., 0., 0.};
        std::set<unsigned int> first_vertices;
        std::map<Key, unsigned int> second_vertices;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() && (face->boundary_id() == first || face->boundary_id() == second))
                {
                  const bool is_first = face->boundary_id() == first;
                  sums[is_first ? 0 : 2] += face->center()[direction];
                  sums[is_first ? 1 : 3] += 1.;
                }
        MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, comm);
        translations[k][direction] = sums[2] / sums[3] - sums[0] / sums[1];
        for (const auto &cell : tria.active_cell_iterators())
          if (!cell->is_artificial())
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary())
                for (const unsigned int v : face->vertex_indices())
                  {
                    if (face->boundary_id() == first)
                      first_vertices.insert(face->vertex_index(v));
                    else if (face->boundary_id() == second)
                      second_vertices[key(face->vertex(v))] = face->vertex_index(v);
                  }
        // The vertex at a position, looking in the neighbouring bins too:
        // rounding may split equal points.
        const auto find_vertex = [&](const Point<3> &x) -> const unsigned int * {
          const Key centre = key(x);
          for (long long a = -1; a <= 1; ++a)
            for (long long b = -1; b <= 1; ++b)
              for (long long c = -1; c <= 1; ++c)
                {
                  const auto it = second_vertices.find(Key{{centre[0] + a, centre[1] + b, centre[2] + c}});
                  if (it != second_vertices.end())
                    return &it->second;
                }
          return nullptr;
        };
        for (const unsigned int v : first_vertices)
          if (const unsigned int *image = find_vertex(tria.get_vertices()[v] + translations[k]))
            {
              std::array<int, 3> forward{{0, 0, 0}}, backward{{0, 0, 0}};
              forward[k]  = 1;
              backward[k] = -1;
              step[v].emplace_back(*image, forward);
              step[*image].emplace_back(v, backward);
            }
      }

    // All combinations of steps (an edge or corner vertex has up to seven
    // images), breadth first from each vertex.
    for (unsigned int v = 0; v < step.size(); ++v)
      {
        if (step[v].empty())
          continue;
        std::vector<Image> found{Image{v, {{0, 0, 0}}}};
        for (std::size_t n = 0; n < found.size(); ++n)
          for (const auto &[w, periods] : step[found[n].vertex])
            {
              Image next{w, found[n].periods};
              for (unsigned int k = 0; k < 3; ++k)
                next.periods[k] += periods[k];
              if (std::none_of(found.begin(), found.end(), [&](const Image &i) {
                    return i.vertex == next.vertex && i.periods == next.periods;
                  }) && std::all_of(next.periods.begin(), next.periods.end(),
                                    [](int p) { return std::abs(p) <= 1; }))
                found.push_back(next);
            }
        images[v].assign(found.begin() + 1, found.end());
      }
    return images;
  }

  void ParticleFluidExchange::add_periodic_pair(const unsigned int first_id,
                                                const unsigned int second_id,
                                                const unsigned int direction)
  {
    impl->periodic_pairs.push_back({{first_id, second_id, direction}});
    impl->mesh_data.current = false;
  }

  unsigned long long ParticleFluidExchange::gather(const std::vector<ExchangeParticle> &particles)
  {
    const auto &tria = impl->dofs.get_triangulation();
    MPI_Comm    comm = tria.get_communicator();
    // A new handler only when the fluid mesh was refined or repartitioned
    // since the last call; otherwise the old one is emptied (its particle ids
    // start again from 0), which gives the same particles in the same order.
    if (!impl->handler || !impl->handler_current)
      {
        impl->handler = std::make_unique<Particles::ParticleHandler<3>>(
          tria, impl->mapping, layout.registry.doubles_per_particle());
        // Boxes around this rank's cells, from level 1 when the mesh has one
        // (a mesh of coarse cells only has level 0: asking for level 1 there
        // is an out-of-range level that deal.II's debug build refuses).
        const unsigned int box_level = std::min(1u, tria.n_global_levels() - 1);
        const auto         boxes     = GridTools::compute_mesh_predicate_bounding_box(
          tria, IteratorFilters::LocallyOwnedCell(), box_level, true, 4);
        impl->global_boxes    = Utilities::MPI::all_gather(comm, boxes);
        impl->handler_current = true;
      }
    else
      impl->handler->clear();
    impl->n_given = particles.size();

    const unsigned int        rank = Utilities::MPI::this_mpi_process(comm);
    std::vector<Point<3>>     positions(particles.size());
    std::vector<std::vector<double>> properties(particles.size(), std::vector<double>(layout.registry.doubles_per_particle()));
    for (std::size_t i = 0; i < particles.size(); ++i)
      {
        const auto &p = particles[i];
        positions[i]  = Point<3>(p.position.x, p.position.y, p.position.z);
        auto &prop    = properties[i];
        prop[layout.volume] = p.volume;
        for (unsigned int d = 0; d < 3; ++d)
          {
            prop[layout.velocity + d] = p.velocity[d];
            prop[layout.force + d]    = p.reaction_force[d];
          }
        prop[layout.drag]  = p.drag_coefficient;
        prop[layout.rank]  = rank;
        prop[layout.index] = i;
      }
    impl->handler->insert_global_particles(positions, impl->global_boxes, properties);
    impl->handler->update_cached_numbers();
    const unsigned long long given = Utilities::MPI::sum<unsigned long long>(particles.size(), comm);
    return given - impl->handler->n_global_particles();
  }

  void ParticleFluidExchange::Implementation::lumped_mass(
    const AffineConstraints<double> &hanging, const IndexSet &owned, const IndexSet &relevant,
    FEValues<3> &fe_values, TrilinosWrappers::MPI::Vector &lumped) const
  {
    const DoFHandler<3> &dof_handler = dofs;
    const auto          &fe          = dof_handler.get_fe();
    MPI_Comm             comm        = dof_handler.get_triangulation().get_communicator();
    const unsigned int   n_dofs      = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    const unsigned int n_q = fe_values.n_quadrature_points;
    lumped.reinit(owned, relevant, comm, true);
    {
      Vector<double> cell_mass(n_dofs);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            cell_mass = 0.;
            for (unsigned int q = 0; q < n_q; ++q)
              for (unsigned int i = 0; i < n_dofs; ++i)
                cell_mass(i) += fe_values.shape_value(i, q) * fe_values.JxW(q);
            cell->get_dof_indices(dof_indices);
            hanging.distribute_local_to_global(cell_mass, dof_indices, lumped);
          }
      lumped.compress(VectorOperation::add);
    }
  }

  void ParticleFluidExchange::Implementation::smooth(
    std::vector<TrilinosWrappers::MPI::Vector> &rhs, const TrilinosWrappers::MPI::Vector &lumped,
    const AffineConstraints<double> &hanging, const IndexSet &owned,
    const IndexSet &relevant) const
  {
    const DoFHandler<3> &dof_handler = dofs;
    const auto          &fe          = dof_handler.get_fe();
    MPI_Comm             comm        = dof_handler.get_triangulation().get_communicator();
    const unsigned int   n_dofs      = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    auto &md = mesh_data;
    if (!md.smoothing_matrix)
      {
        const double T = bandwidth * bandwidth / 4.;
        const double h = mesh_data.smallest_cell;
        // Steps of tau <= h^2 / 8: many small implicit steps approach the
        // Gaussian of the heat kernel (one big step would leave a cusp).
        md.smoothing_steps =
          static_cast<unsigned int>(std::max(2., std::ceil(8. * T / (h * h))));
        const double tau   = T / md.smoothing_steps;
        DynamicSparsityPattern dsp(relevant);
        DoFTools::make_sparsity_pattern(dof_handler, dsp, hanging, false);
        SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
        md.smoothing_matrix = std::make_unique<TrilinosWrappers::SparseMatrix>();
        md.smoothing_matrix->reinit(owned, owned, dsp, comm);
        FEValues<3> fe_grad(mapping, fe, QGauss<3>(fe.degree + 1),
                            update_values | update_gradients | update_JxW_values);
        FullMatrix<double> local(n_dofs, n_dofs);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_grad.reinit(cell);
              local = 0.;
              for (unsigned int q = 0; q < fe_grad.n_quadrature_points; ++q)
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    local(i, i) += fe_grad.shape_value(i, q) * fe_grad.JxW(q); // lumped mass
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      local(i, j) += tau * fe_grad.shape_grad(i, q) * fe_grad.shape_grad(j, q) *
                                     fe_grad.JxW(q);
                  }
              cell->get_dof_indices(dof_indices);
              hanging.distribute_local_to_global(local, dof_indices, *md.smoothing_matrix);
            }
        md.smoothing_matrix->compress(VectorOperation::add);
        md.smoothing_preconditioner = std::make_unique<TrilinosWrappers::PreconditionAMG>();
        md.smoothing_preconditioner->initialize(*md.smoothing_matrix);
      }
    TrilinosWrappers::MPI::Vector b(owned, comm), q(owned, comm);
    for (auto &channel : rhs)
      {
        b = 0.;
        for (const auto i : owned)
          if (!hanging.is_constrained(i))
            b[i] = channel[i];
        b.compress(VectorOperation::insert);
        const double scale = b.l2_norm();
        if (scale == 0.)
          continue;
        for (unsigned int k = 0; k < md.smoothing_steps; ++k)
          {
            q = 0.;
            SolverControl control(1000, 1e-13 * b.l2_norm());
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            cg.solve(*md.smoothing_matrix, q, b, *md.smoothing_preconditioner);
            for (const auto i : owned)
              b[i] = hanging.is_constrained(i) ? 0. : lumped[i] * q[i];
            b.compress(VectorOperation::insert);
          }
        channel = 0.;
        for (const auto i : owned)
          channel[i] = b[i];
        channel.compress(VectorOperation::insert);
      }
  }

  double ParticleFluidExchange::Implementation::field_integral(
    const TrilinosWrappers::MPI::Vector &solid_fraction, const IndexSet &owned,
    const IndexSet &relevant, FEValues<3> &fe_values) const
  {
    const DoFHandler<3> &dof_handler = dofs;
    MPI_Comm             comm        = dof_handler.get_triangulation().get_communicator();
    const unsigned int   n_q         = fe_values.n_quadrature_points;
    TrilinosWrappers::MPI::Vector ghosted(owned, relevant, comm);
    ghosted = solid_fraction;
    double              integral = 0.;
    std::vector<double> values(n_q);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(ghosted, values);
          for (unsigned int q = 0; q < n_q; ++q)
            integral += values[q] * fe_values.JxW(q);
        }
    return Utilities::MPI::sum(integral, comm);
  }

  ParticleFluidExchange::Implementation::ParticleSums
  ParticleFluidExchange::Implementation::deposit(const Channels &channels,
                                                 const AffineConstraints<double> &hanging,
                                                 FEValues<3> &fe_values,
                                                 std::vector<TrilinosWrappers::MPI::Vector> &rhs) const
  {
    const DoFHandler<3> &dof_handler = dofs;
    const auto          &fe          = dof_handler.get_fe();
    const unsigned int   n_dofs      = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    ParticleSums                         sums;
    std::vector<double>                  value(channels.n);
    // What one particle deposits, and its part of the particles' sums.
    const auto channel_values = [&](const ArrayView<const double> &prop)
      -> const std::vector<double> & {
      const double V = prop[layout.volume];
      value[0]       = V;
      for (unsigned int d = 0; d < 3; ++d)
        {
          if (channels.with_velocity)
            value[channels.first_velocity + d] = V * prop[layout.velocity + d];
          if (channels.with_force)
            value[channels.first_force + d] = prop[layout.force + d];
        }
      if (channels.with_drag)
        value[channels.first_drag] = prop[layout.drag];
      sums.volume += V;
      sums.drag += prop[layout.drag];
      for (unsigned int d = 0; d < 3; ++d)
        {
          sums.momentum[d] += V * prop[layout.velocity + d];
          sums.force[d] += prop[layout.force + d];
        }
      return value;
    };

    std::vector<SupportCell> support;
    for (const auto &home : dof_handler.active_cell_iterators())
      {
        if (!home->is_locally_owned())
          continue;
        const auto particles = handler->particles_in_cell(home);
        if (particles.begin() == particles.end())
          continue;
        if (scheme != ProjectionScheme::kernel)
          {
            // Centroid: b_i += q_p phi_i(xi_p) in the particle's own cell.
            home->get_dof_indices(dof_indices);
            std::vector<Vector<double>> locals(channels.n, Vector<double>(n_dofs));
            for (const auto &particle : particles)
              {
                channel_values(particle.get_properties());
                const Point<3> xi = particle.get_reference_location();
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    const double phi = fe.shape_value(i, xi);
                    for (unsigned int c = 0; c < channels.n; ++c)
                      locals[c](i) += value[c] * phi;
                  }
              }
            for (unsigned int c = 0; c < channels.n; ++c)
              hanging.distribute_local_to_global(locals[c], dof_indices, rhs[c]);
            continue;
          }
        support_cells(home, channels.n, fe_values, support);
        for (const auto &particle : particles)
          deposit_with_kernel(particle.get_location(), particle.get_reference_location(),
                              channel_values(particle.get_properties()), support);
        Vector<double> local(n_dofs);
        for (auto &sc : support)
          {
            sc.cell->get_dof_indices(dof_indices);
            for (unsigned int ch = 0; ch < channels.n; ++ch)
              {
                for (unsigned int i = 0; i < n_dofs; ++i)
                  local(i) = sc.local[i * channels.n + ch];
                hanging.distribute_local_to_global(local, dof_indices, rhs[ch]);
              }
          }
      }
    for (auto &b : rhs)
      b.compress(VectorOperation::add);
    return sums;
  }

  void ParticleFluidExchange::Implementation::support_cells(
    const DoFHandler<3>::active_cell_iterator &home, const unsigned int n_channels,
    FEValues<3> &fe_values, std::vector<SupportCell> &support) const
  {
    const DoFHandler<3> &dof_handler = dofs;
    const auto          &mesh        = current_mesh_data();
    const unsigned int   n_q         = fe_values.n_quadrature_points;
    const unsigned int   n_dofs      = dof_handler.get_fe().n_dofs_per_cell();
    // The home cell and every cell sharing a vertex with it, or with one of
    // its vertices' periodic images; a cell across a periodic face is shifted
    // back by the periods between it and the home cell.
    std::set<std::tuple<int, int, std::array<int, 3>>> cells;
    for (const unsigned int v : home->vertex_indices())
      {
        const unsigned int vertex = home->vertex_index(v);
        for (const auto &c : mesh.vertex_to_cells[vertex])
          if (!c->is_artificial())
            cells.emplace(c->level(), c->index(), std::array<int, 3>{{0, 0, 0}});
        for (const auto &image : mesh.images[vertex])
          for (const auto &c : mesh.vertex_to_cells[image.vertex])
            if (!c->is_artificial())
              cells.emplace(c->level(), c->index(), image.periods);
      }
    support.resize(cells.size());
    unsigned int s = 0;
    for (const auto &[level, index, periods] : cells)
      {
        SupportCell &sc = support[s++];
        sc.cell         = DoFHandler<3>::active_cell_iterator(&dof_handler.get_triangulation(),
                                                      level, index, &dof_handler);
        Tensor<1, 3> shift;
        for (unsigned int k = 0; k < mesh.translations.size(); ++k)
          shift -= periods[k] * mesh.translations[k];
        sc.is_home = sc.cell == home && shift.norm() == 0.;
        fe_values.reinit(sc.cell);
        sc.x = fe_values.get_quadrature_points();
        for (auto &x : sc.x)
          x += shift;
        sc.box = BoundingBox<3>(sc.x);
        sc.JxW = fe_values.get_JxW_values();
        sc.shape.reinit(n_q, n_dofs);
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int i = 0; i < n_dofs; ++i)
            sc.shape(q, i) = fe_values.shape_value(i, q);
        sc.local.assign(n_dofs * n_channels, 0.);
      }
  }

  void ParticleFluidExchange::Implementation::deposit_with_kernel(
    const Point<3> &xp, const Point<3> &xi, const std::vector<double> &value,
    std::vector<SupportCell> &support) const
  {
    // (Locals, not members, in the loops: the compiler then keeps them in
    // registers across the stores into the deposits.)
    const auto        &fe     = dofs.get_fe();
    const unsigned int n_dofs = fe.n_dofs_per_cell();
    const unsigned int n_q    = support.empty() ? 0 : support[0].JxW.size();
    const unsigned int n_ch   = value.size();
    const double       R      = radius;
    // Beyond this squared distance the kernel is zero: skip its square root
    // and division (the margin, far above round-off, leaves every weight as
    // it was).
    const double R2_beyond = R * R * (1. + 1e-9);
    weights.resize(support.size() * n_q);
    within.clear();
    double *const w_cq  = weights.data();
    double        total = 0.;
    for (unsigned int c = 0; c < support.size(); ++c)
      {
        // A support radius is at most a cell, so the kernel reaches at most 8
        // of the up to 27 cells. A cell whose quadrature points all lie
        // beyond R (with a margin far above round-off) would only add zero
        // weights: skipping it leaves every sum as it was, to the bit.
        if (box_distance_square(support[c].box, xp) > R2_beyond)
          continue;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double d2 = support[c].x[q].distance_square(xp);
            if (d2 > R2_beyond)
              continue;
            const double w = kernel(std::sqrt(d2) / R) * support[c].JxW[q];
            if (w == 0.)
              continue;
            w_cq[c * n_q + q] = w;
            within.push_back(c * n_q + q);
            total += w;
          }
      }
    if (!(total > 0.))
      {
        // No quadrature point within reach (R far below the cell size):
        // deposit at the centre, b_i = q_p phi_i(xi_p).
        for (auto &sc : support)
          if (sc.is_home)
            for (unsigned int i = 0; i < n_dofs; ++i)
              for (unsigned int ch = 0; ch < n_ch; ++ch)
                sc.local[i * n_ch + ch] += value[ch] * fe.shape_value(i, xi);
        return;
      }
    // Normalised over the part of the support inside the domain, so a
    // particle at a wall deposits all of itself (Gao & Sun Eq. 25). The
    // points are visited in the order of the sum above, cell by cell, so
    // every deposit adds up in the same order whatever is skipped.
    std::array<double, max_channels> v;
    for (unsigned int ch = 0; ch < n_ch; ++ch)
      v[ch] = value[ch];
    for (const unsigned int cq : within)
      {
        const unsigned int c     = cq / n_q;
        const unsigned int q     = cq % n_q;
        const double       w     = w_cq[cq] / total;
        double *const      local = support[c].local.data();
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const double wphi = w * support[c].shape(q, i);
            for (unsigned int ch = 0; ch < n_ch; ++ch)
              local[i * n_ch + ch] += v[ch] * wphi;
          }
      }
  }

  unsigned int ParticleFluidExchange::Implementation::solid_fraction_from(
    const TrilinosWrappers::MPI::Vector &volume, const TrilinosWrappers::MPI::Vector &lumped,
    const AffineConstraints<double> &hanging, const IndexSet &owned,
    const double max_solid_fraction, TrilinosWrappers::MPI::Vector &solid_fraction) const
  {
    MPI_Comm     comm    = dofs.get_triangulation().get_communicator();
    unsigned int clipped = 0;
    solid_fraction.reinit(owned, comm);
    for (const auto i : owned)
      if (!hanging.is_constrained(i))
        {
          double s = volume[i] / lumped[i];
          if (s > max_solid_fraction)
            {
              s = max_solid_fraction;
              ++clipped;
            }
          solid_fraction[i] = s;
        }
    solid_fraction.compress(VectorOperation::insert);
    hanging.distribute(solid_fraction);
    return Utilities::MPI::sum(clipped, comm);
  }

  Tensor<1, 3> ParticleFluidExchange::Implementation::solid_velocity_from(
    const std::vector<TrilinosWrappers::MPI::Vector> &rhs, const unsigned int first_velocity,
    const AffineConstraints<double> &hanging, const IndexSet &owned,
    std::array<TrilinosWrappers::MPI::Vector, 3> &solid_velocity) const
  {
    MPI_Comm     comm = dofs.get_triangulation().get_communicator();
    Tensor<1, 3> momentum;
    for (unsigned int d = 0; d < 3; ++d)
      {
        auto &u = solid_velocity[d];
        u.reinit(owned, comm);
        for (const auto i : owned)
          if (!hanging.is_constrained(i) && rhs[0][i] > 0.)
            {
              u[i] = rhs[first_velocity + d][i] / rhs[0][i];
              momentum[d] += rhs[first_velocity + d][i];
            }
        u.compress(VectorOperation::insert);
        hanging.distribute(u);
      }
    return momentum;
  }

  Tensor<1, 3> ParticleFluidExchange::Implementation::force_density_from(
    const std::vector<TrilinosWrappers::MPI::Vector> &rhs, const unsigned int first_force,
    const TrilinosWrappers::MPI::Vector &lumped, const AffineConstraints<double> &hanging,
    const IndexSet &owned, const IndexSet &relevant, const DoFHandler<3> &force_dofs,
    TrilinosWrappers::MPI::Vector &force_density) const
  {
    const DoFHandler<3> &dof_handler = dofs;
    const auto          &fe          = dof_handler.get_fe();
    MPI_Comm             comm        = dof_handler.get_triangulation().get_communicator();
    // Force per volume on the scalar dofs, then copied node by node into the
    // FE_Q^3 field of the same degree (same nodes, same function).
    Tensor<1, 3>                                 field_force;
    std::array<TrilinosWrappers::MPI::Vector, 3> f;
    for (unsigned int d = 0; d < 3; ++d)
      {
        TrilinosWrappers::MPI::Vector owned_f(owned, comm);
        for (const auto i : owned)
          if (!hanging.is_constrained(i))
            owned_f[i] = rhs[first_force + d][i] / lumped[i];
        owned_f.compress(VectorOperation::insert);
        // The field's integral, from its nodal values: sum_i m_i f_i.
        for (const auto i : owned)
          if (!hanging.is_constrained(i))
            field_force[d] += lumped[i] * owned_f[i];
        hanging.distribute(owned_f);
        f[d].reinit(owned, relevant, comm);
        f[d] = owned_f;
      }
    const auto &vector_fe = force_dofs.get_fe();
    AssertThrow(vector_fe.n_components() == 3 && vector_fe.degree == fe.degree,
                ExcMessage("the force field must be FE_Q^3 of the porosity's degree"));
    const IndexSet force_owned = force_dofs.locally_owned_dofs();
    force_density.reinit(force_owned, comm);
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> vector_indices(vector_fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dof_indices);
          DoFHandler<3>::active_cell_iterator(&dof_handler.get_triangulation(), cell->level(),
                                              cell->index(), &force_dofs)
            ->get_dof_indices(vector_indices);
          for (unsigned int j = 0; j < vector_indices.size(); ++j)
            if (force_owned.is_element(vector_indices[j]))
              {
                const auto ci = vector_fe.system_to_component_index(j);
                force_density[vector_indices[j]] = f[ci.first][dof_indices[ci.second]];
              }
        }
    force_density.compress(VectorOperation::insert);
    return field_force;
  }

  double ParticleFluidExchange::Implementation::drag_density_from(
    const TrilinosWrappers::MPI::Vector &deposit, const TrilinosWrappers::MPI::Vector &lumped,
    const AffineConstraints<double> &hanging, const IndexSet &owned,
    TrilinosWrappers::MPI::Vector &drag_density) const
  {
    drag_density.reinit(owned, dofs.get_triangulation().get_communicator());
    double field_drag = 0.; // sum_i m_i beta_i = sum_i b_i
    for (const auto i : owned)
      if (!hanging.is_constrained(i))
        {
          drag_density[i] = deposit[i] / lumped[i];
          field_drag += deposit[i];
        }
    drag_density.compress(VectorOperation::insert);
    hanging.distribute(drag_density);
    return field_drag;
  }

  ProjectionReport ParticleFluidExchange::project(
    TrilinosWrappers::MPI::Vector &solid_fraction, const double max_solid_fraction,
    std::array<TrilinosWrappers::MPI::Vector, 3> *solid_velocity, const DoFHandler<3> *force_dofs,
    TrilinosWrappers::MPI::Vector *force_density,
    TrilinosWrappers::MPI::Vector *drag_density) const
  {
    const DoFHandler<3> &dof_handler = impl->dofs;
    MPI_Comm             comm        = dof_handler.get_triangulation().get_communicator();
    const auto          &fe          = dof_handler.get_fe();

    const auto &mesh = impl->current_mesh_data();
    // The support must stay within the vertex neighbours of the home cell.
    if (impl->scheme == ProjectionScheme::kernel &&
        impl->radius > mesh.smallest_cell * (1. + 1e-10))
      throw std::invalid_argument("the kernel support radius " + std::to_string(impl->radius) +
                                  " m exceeds the smallest fluid cell (" +
                                  std::to_string(mesh.smallest_cell) +
                                  " m); allowed: a radius up to the smallest cell size");

    // Kept while the mesh is unchanged.
    const IndexSet                   owned    = dof_handler.locally_owned_dofs();
    const IndexSet                  &relevant = mesh.relevant;
    const AffineConstraints<double> &hanging  = mesh.hanging;

    // Deposited quantities ("channels"): volume, then V_p v_p, then F_p, then k_p.
    Implementation::Channels channels;
    channels.with_velocity  = solid_velocity != nullptr;
    channels.with_force     = force_density != nullptr;
    channels.with_drag      = drag_density != nullptr;
    channels.first_velocity = 1;
    channels.first_force    = channels.with_velocity ? 4 : 1;
    channels.first_drag     = channels.first_force + (channels.with_force ? 3 : 0);
    channels.n              = channels.first_drag + (channels.with_drag ? 1 : 0);
    std::vector<TrilinosWrappers::MPI::Vector> rhs(channels.n);
    for (auto &b : rhs)
      b.reinit(owned, relevant, comm, true); // writable ghosts: deposits travel to owners

    // One FEValues for the deposit, the lumped mass and the field integral:
    // its cell-similarity state is part of what makes the numbers repeat
    // exactly.
    const QGauss<3> quadrature(fe.degree + 2);
    FEValues<3>     fe_values(impl->mapping, fe, quadrature,
                          update_values | update_quadrature_points | update_JxW_values);
    const Implementation::ParticleSums sums = impl->deposit(channels, hanging, fe_values, rhs);

    // The lumped-mass projection q_i = b_i / m_i, m_i = integral of phi_i: local,
    // never negative, and conservative, since the integral of q_h is
    // sum_i m_i q_i = sum_i b_i. (A consistent L2 projection rings near steep
    // deposits and can turn a solid fraction negative.)
    TrilinosWrappers::MPI::Vector lumped;
    impl->lumped_mass(hanging, owned, relevant, fe_values, lumped);

    // Diffusion-based coarse graining (Sun & Xiao 2015, Eqs. 5-9): the field
    // q = M_L^-1 b is diffused for a pseudo time T = b^2 / 4 in implicit steps
    // (M_L + tau K) q_k+1 = M_L q_k with zero flux through the walls. Each step
    // keeps sum_i m_i q_i (the rows of K sum to zero), so every channel stays
    // conserved; on a uniform hex mesh M_L + tau K is an M-matrix, so a solid
    // fraction stays non-negative. The width of the deposit is then b, not the
    // cell: a single particle's self-interaction no longer depends on where in
    // its cell it sits. Here the b's are updated in place: b <- M_L q_n.
    if (impl->bandwidth > 0.)
      impl->smooth(rhs, lumped, hanging, owned, relevant);

    ProjectionReport report;
    report.clipped_nodes = impl->solid_fraction_from(rhs[0], lumped, hanging, owned,
                                                     max_solid_fraction, solid_fraction);
    if (channels.with_velocity)
      report.field_momentum =
        impl->solid_velocity_from(rhs, channels.first_velocity, hanging, owned, *solid_velocity);
    if (channels.with_force)
      report.field_force = impl->force_density_from(rhs, channels.first_force, lumped, hanging,
                                                    owned, relevant, *force_dofs, *force_density);
    if (channels.with_drag)
      {
        report.field_drag    = Utilities::MPI::sum(impl->drag_density_from(rhs[channels.first_drag],
                                                                        lumped, hanging, owned,
                                                                        *drag_density),
                                                comm);
        report.particle_drag = Utilities::MPI::sum(sums.drag, comm);
      }

    report.deposited_volume  = Utilities::MPI::sum(sums.volume, comm);
    report.particle_momentum = Utilities::MPI::sum(sums.momentum, comm);
    report.particle_force    = Utilities::MPI::sum(sums.force, comm);
    report.field_momentum    = Utilities::MPI::sum(report.field_momentum, comm);
    report.field_force       = Utilities::MPI::sum(report.field_force, comm);

    // The integral of the field itself, by quadrature (the conservation check).
    report.field_integral = impl->field_integral(solid_fraction, owned, relevant, fe_values);
    return report;
  }

  std::vector<FluidSample> ParticleFluidExchange::sample(const VansSolver &fluid,
                                                          const bool viscous_divergence) const
  {
    const auto &tria = impl->dofs.get_triangulation();
    MPI_Comm    comm = tria.get_communicator();
    std::map<unsigned int, std::vector<double>> outgoing;
    std::vector<Point<3>>    reference;
    std::vector<FluidSample> samples;
    std::vector<const double *> props;
    for (const auto &cell : tria.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        const auto particles = impl->handler->particles_in_cell(cell);
        if (particles.begin() == particles.end())
          continue;
        reference.clear();
        props.clear();
        for (const auto &particle : particles)
          {
            reference.push_back(particle.get_reference_location());
            props.push_back(particle.get_properties().data());
          }
        fluid.sample_cell(cell, reference, samples, viscous_divergence);
        for (unsigned int k = 0; k < samples.size(); ++k)
          {
            const FluidSample &s   = samples[k];
            auto              &buf = outgoing[static_cast<unsigned int>(props[k][layout.rank])];
            buf.push_back(props[k][layout.index]);
            for (unsigned int d = 0; d < 3; ++d)
              buf.push_back(s.velocity[d]);
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                buf.push_back(s.velocity_gradient[i][j]);
            for (unsigned int d = 0; d < 3; ++d)
              buf.push_back(s.pressure_gradient[d]);
            for (unsigned int d = 0; d < 3; ++d)
              buf.push_back(s.viscous_divergence[d]);
            buf.push_back(s.porosity);
            for (unsigned int d = 0; d < 3; ++d)
              buf.push_back(s.porosity_gradient[d]);
          }
      }
    const auto incoming = Utilities::MPI::some_to_some(comm, outgoing);
    std::vector<FluidSample> result(impl->n_given);
    for (const auto &[from, buf] : incoming)
      for (std::size_t k = 0; k + sample_stride <= buf.size(); k += sample_stride)
        {
          const double *b = buf.data() + k;
          FluidSample  &s = result.at(static_cast<std::size_t>(b[0]));
          s.found         = true;
          unsigned int n  = 1;
          for (unsigned int d = 0; d < 3; ++d)
            s.velocity[d] = b[n++];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              s.velocity_gradient[i][j] = b[n++];
          for (unsigned int d = 0; d < 3; ++d)
            s.pressure_gradient[d] = b[n++];
          for (unsigned int d = 0; d < 3; ++d)
            s.viscous_divergence[d] = b[n++];
          s.porosity = b[n++];
          for (unsigned int d = 0; d < 3; ++d)
            s.porosity_gradient[d] = b[n++];
        }
    return result;
  }
} // namespace sluice
