#pragma once
// Everything a scene file (.prm) can say, as plain data.
//
// The struct is filled and checked in scene_parameters.cc with deal.II's
// ParameterHandler; the rest of the code never sees the ParameterHandler, so the
// DEM kernels do not pay for its headers. All quantities are SI.

#include <sluice/core/output_files.h>
#include <sluice/core/vector3.h>
#include <sluice/core/coupling_parameters.h>
#include <sluice/core/fluid_parameters.h>
#include <sluice/core/mesh_wall_parameters.h>
#include <sluice/core/clump_parameters.h>
#include <sluice/core/stream_parameters.h>
#include <sluice/core/wear_parameters.h>
#include <sluice/core/imported_field_parameters.h>
#include <sluice/core/run_stopped.h>
#include <sluice/core/sph_parameters.h>

#include <array>
#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace sluice
{
  /// A number as a person would write it (6 significant digits), for messages.
  std::string to_text(double value);

  /// Bad input: the message names the file, the entry and the allowed range.
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  enum class NormalContactModel
  {
    linear,       // linear spring-dashpot, Gao & Sun Eqs. 4-11
    hertz_mindlin // Hertz normal, Mindlin tangential, Johnson (1985)
  };

  enum class RollingResistanceModel
  {
    none,
    constant_torque, // Ai et al. (2011) model A
    viscous          // torque grows with the relative rolling speed
  };

  enum class InsertionMethod
  {
    lattice, // jittered simple-cubic lattice filling the region
    random,  // random sequential addition without overlap
    file,    // a CSV file with one particle per line
    list     // the same rows written inline in the .prm
  };

  enum class ValidationCase
  {
    none,
    hertz_impact,       // contact duration and maximum overlap vs Hertz theory
    restitution,        // rebound / impact normal speed vs the set restitution
    sliding_to_rolling, // final speed vs 5/7 v0
    settle,             // packing fraction of a settled bed, nothing lost
    mesh_plane_equivalence, // a triangulated plane against the plane, step by step
    energy_balance,         // the energy bookkeeping closes, at dt and dt/2
    clump_impact,           // a clump's rebound and spin vs a rigid-body integration
    clump_rotation          // a free asymmetric clump's flips vs the closed form
  };

  /// One plane wall as the scene describes it: a point on it and the unit
  /// normal pointing into the domain at t = 0, its material, and its motion:
  /// velocity and angular velocity (about the point) as expressions in t, each
  /// three comma-separated components, or empty for a wall at rest.
  struct PlaneWall
  {
    Vec3         point;
    Vec3         normal;
    unsigned int material = 0;
    std::string  name;
    std::string  velocity, angular_velocity;
  };

  /// One particle as written in a CSV file or an inline list.
  struct ParticleRecord
  {
    Vec3         position;
    double       radius = 0.;
    unsigned int type   = 0;
    Vec3         velocity;
    Vec3         angular_velocity;
    // A clump (clump_parameters.h): its template, scale and orientation (a
    // unit quaternion w, x, y, z, body to space); 'radius' is then the
    // bounding radius, set by the DEM from the template.
    unsigned int          clump_template = 0;
    double                clump_scale    = 1.;
    std::array<double, 4> orientation{{1., 0., 0., 0.}};
  };

  /// One class of a discrete size mixture ('insertion/size classes'): its
  /// radius, its share of the inserted mass and its material type.
  struct SizeClass
  {
    double       radius        = 0.;
    double       mass_fraction = 0.;
    unsigned int type          = 0;
  };

  /// A contact property given for one pair of material types.
  struct PairOverride
  {
    unsigned int type_a = 0, type_b = 0;
    double       value  = 0.;
  };

  /// Which solvers a scene builds; nothing else is constructed.
  enum class Physics
  {
    dem,    // particles only: no fluid mesh, no fluid system
    fluid,  // the averaged Navier-Stokes equations only, porosity given
    cfd_dem, // both, coupled through the particle-fluid exchange
    sph      // an SPH fluid alone (the 'sph' subsection; doc/sph.md)
  };

  struct SceneParameters
  {
    std::string file_name; // the .prm this was read from, for messages
    Physics     physics = Physics::dem;

    // subsection simulation
    double end_time                = 1.;
    bool   automatic_time_step     = true;
    double time_step               = 0.; // set when not automatic
    double time_step_fraction      = 0.02;
    double maximum_time_step_ratio = 0.1;
    double restitution_accuracy    = 0.005;
    double maximum_overlap         = 0.2; // of the smaller radius, during the run
    Vec3   gravity{0., 0., -9.81};
    double characteristic_velocity = 1.;

    // subsection domain
    Vec3                lower_corner{0., 0., 0.};
    Vec3                upper_corner{1., 1., 1.};
    std::array<bool, 3> periodic{{false, false, false}};
    bool                outlet = false; // particles may leave the domain

    // subsection materials (one entry per material type)
    std::vector<double> density;
    std::vector<double> young_modulus;
    std::vector<double> poisson_ratio;

    // subsection contact
    NormalContactModel        normal_model = NormalContactModel::hertz_mindlin;
    double                    restitution  = 0.5;
    double                    friction     = 0.5;
    double                    rolling_friction = 0.;
    RollingResistanceModel    rolling_model = RollingResistanceModel::none;
    std::vector<PairOverride> restitution_pairs, friction_pairs, rolling_friction_pairs;
    double                    linear_normal_stiffness = 0.; // 0: from E* and v_char
    double                    tangential_stiffness_ratio = 2. / 7.;
    double                    neighbour_skin           = 0.; // 0: 0.2 * largest radius

    // subsection walls
    bool                   box_walls     = true;
    unsigned int           wall_material = 0;
    std::vector<PlaneWall> walls; // box faces first, then the extra planes
    std::vector<MeshWallParameters> meshes; // triangle-mesh walls, after the planes

    // subsection insertion
    InsertionMethod             insertion_method = InsertionMethod::lattice;
    unsigned long long          n_particles      = 0;
    Vec3                        region_lower, region_upper;
    double                      radius     = 0.001;
    double                      radius_max = 0.; // > radius: uniform in [radius, radius_max]
    unsigned int                particle_type = 0;
    std::vector<SizeClass>      size_classes; // empty: 'radius' (and 'radius max')
    Vec3                        initial_velocity, initial_angular_velocity;
    double                      maximum_initial_overlap = 0.05; // of the smaller radius
    double                      lattice_jitter = 0.1;
    double                      lattice_spacing = 0.; // 0: 2.1 largest radii
    unsigned int                seed           = 1;
    std::string                 particle_file;
    std::vector<ParticleRecord> particle_list; // filled for 'file' and 'list'

    // subsection output
    std::string  output_directory = "output";
    std::string  base_name        = "particles";
    IfOutputExists if_output_exists = IfOutputExists::new_directory;
    double       vtu_interval     = 0.;
    double       csv_interval     = 0.;
    double       particle_csv_interval = 0.;
    bool         progress         = true;
    unsigned int summary_precision = 8;

    // subsection checkpoint
    unsigned long long checkpoint_step_interval = 0;  // [steps], 0: none
    double             checkpoint_time_interval = 0.; // [s], 0: none
    unsigned int       checkpoints_kept         = 2;
    std::string        restart_from;                  // a checkpoint directory, or 'latest'

    // subsection validation
    ValidationCase validation          = ValidationCase::none;
    double         validation_tolerance = 0.;
    double         packing_fraction_min = 0.55;
    double         packing_fraction_max = 0.64;
    double         kinetic_energy_threshold = 1e-6;

    // subsection wear and breakage
    WearParameters wear;
    // subsection stream
    StreamParameters stream;
    // subsection clumps
    ClumpParameters clumps;
    // subsection imported field
    ImportedFieldParameters imported_field;
    SphParameters           sph;

    // the fluid subsections
    FluidParameters fluid;
    // the cfd-dem subsections
    CouplingParameters coupling;

    unsigned int n_materials() const { return density.size(); }
    /// Whether any pair has a sliding friction > 0 (else no tangential history).
    bool any_friction() const { return any_positive(friction, friction_pairs); }
    /// Whether any pair has a rolling friction > 0 (else no rolling torque).
    bool any_rolling_friction() const
    {
      return any_positive(rolling_friction, rolling_friction_pairs);
    }
    static bool any_positive(const double all_pairs, const std::vector<PairOverride> &overrides)
    {
      bool any = all_pairs > 0.;
      for (const auto &o : overrides)
        any = any || o.value > 0.;
      return any;
    }
    double       largest_radius() const;
  };

  /// Reads and checks a scene file. Throws InputError before anything is written.
  SceneParameters read_scene_parameters(const std::string &file_name);

  /// Prints every entry with its default, unit, range and documentation.
  void print_scene_parameters(std::ostream &out);
} // namespace sluice
