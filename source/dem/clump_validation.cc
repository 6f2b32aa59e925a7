// The validation measurements of a clump scene (see the header).

#include <sluice/dem/clump_validation.h>
#include <sluice/dem/eigen_conversion.h>
#include <sluice/dem/particle_exchange.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sluice
{
  namespace
  {
    /// The rigid body's state for the reference integration.
    struct RigidState
    {
      Eigen::Vector3d x, v, L; // L in the body frame
      Eigen::Vector4d q;       // w, x, y, z (not kept normalised between stages)

      RigidState operator+(const RigidState &o) const { return {x + o.x, v + o.v, L + o.L, q + o.q}; }
      RigidState operator*(const double s) const { return {s * x, s * v, s * L, s * q}; }
    };

    Eigen::Quaterniond quaternion(const Eigen::Vector4d &q)
    {
      return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
    }

    /// The right-hand side of a rigid body's motion (Euler's equations in the
    /// body frame, dq/dt = q (0, w_body) / 2) under the normal forces of the
    /// plane walls on its members.
    struct ImpactModel
    {
      std::vector<Eigen::Vector3d> offsets; // members in the body frame, scaled
      std::vector<double>          radii;
      Eigen::Vector3d              I;
      double                       mass = 0.;
      std::vector<Eigen::Vector3d> wall_point, wall_normal;
      std::vector<PairProperties>  pair;
      const ContactProperties     *props = nullptr;
      NormalContactModel           law   = NormalContactModel::linear;

      RigidState rate(const RigidState &s) const
      {
        const Eigen::Quaterniond q      = quaternion(s.q);
        const Eigen::Matrix3d    R      = q.toRotationMatrix();
        const Eigen::Vector3d    w_body = s.L.cwiseQuotient(I), w = R * w_body;
        Eigen::Vector3d          F = Eigen::Vector3d::Zero(), T = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < offsets.size(); ++k)
          for (std::size_t p = 0; p < wall_point.size(); ++p)
            {
              const Eigen::Vector3d lever = R * offsets[k], c = s.x + lever;
              const double delta = radii[k] - (c - wall_point[p]).dot(wall_normal[p]);
              if (delta <= 0.)
                continue;
              const double v_n = (s.v + w.cross(lever)).dot(wall_normal[p]);
              const Eigen::Vector3d f = normal_force(pair[p], delta, radii[k], v_n) * wall_normal[p];
              F += f;
              T += lever.cross(f);
            }
        RigidState d;
        d.x = s.v;
        d.v = F / mass;
        d.L = -w_body.cross(s.L) + R.transpose() * T;
        const Eigen::Quaterniond dq =
          Eigen::Quaterniond(s.q[0], s.q[1], s.q[2], s.q[3]) *
          Eigen::Quaterniond(0., w_body.x(), w_body.y(), w_body.z());
        d.q = 0.5 * Eigen::Vector4d(dq.w(), dq.x(), dq.y(), dq.z());
        return d;
      }

      /// The DEM's normal law (contact_law.h) for a member against a wall,
      /// whose effective mass is the member's: the body's.
      double normal_force(const PairProperties &pp, const double delta, const double R,
                          const double v_n) const
      {
        if (law == NormalContactModel::hertz_mindlin)
          {
            const double S_n = 2. * pp.E_star * std::sqrt(R * delta);
            return (2. / 3.) * S_n * delta -
                   2. * sqrt_five_sixths * pp.damping_ratio * std::sqrt(S_n * mass) * v_n;
          }
        const double k_n = props->linear_stiffness(pp, R, mass);
        return k_n * delta - 2. * pp.damping_ratio * std::sqrt(k_n * mass) * v_n;
      }
    };

    RigidState runge_kutta(const ImpactModel &model, RigidState s, const double h)
    {
      const RigidState k1 = model.rate(s), k2 = model.rate(s + k1 * (0.5 * h)),
                       k3 = model.rate(s + k2 * (0.5 * h)), k4 = model.rate(s + k3 * h);
      s   = s + (k1 + k2 * 2. + k3 * 2. + k4) * (h / 6.);
      s.q = s.q.normalized();
      return s;
    }

    std::string check_line(const std::string &name, const double value, const double reference,
                           const double error)
    {
      std::ostringstream s;
      s.precision(8);
      s << "check: " << name << " value=" << value << " reference=" << reference
        << " error=" << error;
      return s.str();
    }
  } // namespace

  ClumpValidation::ClumpValidation(const SceneParameters &p)
    : parameters(p)
  {}

  ClumpValidation::Body ClumpValidation::gather_body(const DemSystem &dem)
  {
    const ClumpSystem     &C = *dem.clumps;
    const ParticleStorage &B = C.bodies;
    double                 local[21] = {};
    for (unsigned int b = 0; b < B.n_local; ++b)
      if (B.id[b] == 0)
        {
          const RigidRotation r = C.rotation_of(b);
          for (unsigned int d = 0; d < 3; ++d)
            {
              local[d]      = B.position[b][d];
              local[3 + d]  = B.velocity[b][d];
              local[6 + d]  = B.angular_velocity[b][d];
              local[13 + d] = r.body_momentum[d];
              local[16 + d] = C.inertia_of(b)[d];
            }
          local[9]  = r.orientation.w();
          local[10] = r.orientation.x();
          local[11] = r.orientation.y();
          local[12] = r.orientation.z();
          local[19] = B.mass[b];
          local[20] = C.scale_of(b);
        }
    double g[21];
    MPI_Allreduce(local, g, 21, MPI_DOUBLE, MPI_SUM, dem.comm);
    Body s;
    s.x    = Vec3(g[0], g[1], g[2]);
    s.v    = Vec3(g[3], g[4], g[5]);
    s.w    = Vec3(g[6], g[7], g[8]);
    s.q    = Eigen::Vector4d(g[9], g[10], g[11], g[12]);
    s.L    = Eigen::Vector3d(g[13], g[14], g[15]);
    s.I    = Eigen::Vector3d(g[16], g[17], g[18]);
    s.mass = g[19];
    return s;
  }

  void ClumpValidation::observe(const DemSystem &dem)
  {
    if (!active())
      return;
    const Body   s = gather_body(dem);
    const double t = dem.time();
    if (!started)
      {
        initial       = s;
        started       = true;
        previous_time = t;
        previous_L2   = s.L[1];
        return;
      }
    if (parameters.validation != ValidationCase::clump_rotation)
      return;
    // A turn about the intermediate axis, and the energy over the first and
    // the last of them.
    const double turn   = 2. * M_PI * initial.I[1] / initial.L.norm();
    const double E0     = 0.5 * initial.L.cwiseProduct(initial.L).cwiseQuotient(initial.I).sum();
    const double energy = 0.5 * s.L.cwiseProduct(s.L).cwiseQuotient(s.I).sum() / E0 - 1.;
    if (t <= turn)
      {
        first_turn_energy += energy;
        first_turn_steps += 1.;
      }
    if (t > parameters.end_time - turn)
      {
        last_turn_energy += energy;
        last_turn_steps += 1.;
      }
    if ((s.L[1] < 0.) != (previous_L2 < 0.))
      crossings.push_back(t - (t - previous_time) * s.L[1] / (s.L[1] - previous_L2));
    previous_time = t;
    previous_L2   = s.L[1];
    const Eigen::Vector3d L_space  = quaternion(s.q) * s.L;
    const Eigen::Vector3d L0_space = quaternion(initial.q) * initial.L;
    last_momentum_error            = (L_space - L0_space).norm() / L0_space.norm();
  }

  ValidationResult ClumpValidation::finish(const DemSystem &dem) const
  {
    return parameters.validation == ValidationCase::clump_impact ? finish_impact(dem) :
                                                                    finish_rotation();
  }

  ValidationResult ClumpValidation::finish_impact(const DemSystem &dem) const
  {
    const Body end = gather_body(dem);
    // The same body, integrated independently from its initial state.
    ImpactModel model;
    model.I     = initial.I;
    model.mass  = initial.mass;
    model.props = &dem.properties;
    model.law   = parameters.normal_model;
    unsigned int body_type = 0, template_index = 0;
    double       scale = 0.;
    {
      const ClumpSystem &C = *dem.clumps;
      double             local[3] = {};
      for (unsigned int b = 0; b < C.bodies.n_local; ++b)
        if (C.bodies.id[b] == 0)
          {
            local[0] = C.bodies.type[b];
            local[1] = &C.template_of(b) - C.templates.data();
            local[2] = C.scale_of(b);
          }
      double g[3];
      MPI_Allreduce(local, g, 3, MPI_DOUBLE, MPI_SUM, dem.comm);
      body_type      = static_cast<unsigned int>(g[0]);
      template_index = static_cast<unsigned int>(g[1]);
      scale          = g[2];
    }
    const ClumpTemplate &t = dem.clumps->templates[template_index];
    for (std::size_t k = 0; k < t.members.size(); ++k)
      {
        model.offsets.push_back(scale * to_eigen(t.members[k]));
        model.radii.push_back(scale * t.radii[k]);
      }
    for (unsigned int w = 0; w < dem.walls.n_planes(); ++w)
      {
        model.wall_point.push_back(to_eigen(dem.walls[w].point));
        model.wall_normal.push_back(to_eigen(dem.walls[w].normal));
        model.pair.push_back(dem.properties(body_type, dem.walls[w].material));
      }
    RigidState s{to_eigen(initial.x), to_eigen(initial.v), initial.L, initial.q};
    const double       h       = dem.dt / 20.;
    const unsigned long n_steps = std::lround(dem.time() / h);
    for (unsigned long k = 0; k < n_steps; ++k)
      s = runge_kutta(model, s, h);
    const Eigen::Vector3d w_ref = quaternion(s.q) * s.L.cwiseQuotient(model.I);

    // Errors relative to the speed of the impact and to the spin it gives.
    const double v0 = norm(initial.v), w_scale = std::max(w_ref.norm(), 1e-300);
    ValidationResult r;
    r.name      = "clump_impact";
    r.value     = norm(end.w);
    r.reference = w_ref.norm();
    r.error     = (to_eigen(end.w) - w_ref).norm() / w_scale;
    r.checks.push_back(check_line("rebound_velocity_z", end.v.z, s.v.z(),
                                  std::abs(end.v.z - s.v.z()) / v0));
    r.checks.push_back(check_line("rebound_velocity_x", end.v.x, s.v.x(),
                                  std::abs(end.v.x - s.v.x()) / v0));
    r.checks.push_back(check_line("rebound_speed", norm(end.v), s.v.norm(),
                                  (to_eigen(end.v) - s.v).norm() / v0));
    return r;
  }

  ValidationResult ClumpValidation::finish_rotation() const
  {
    ValidationResult r;
    r.name = "clump_rotation";
    if (crossings.size() < 2)
      {
        r.failure = "the body did not flip twice: nothing to measure (a longer 'end time', "
                    "or a spin nearer the intermediate axis)";
        r.error   = 1.;
        return r;
      }
    const double flip_time = (crossings.back() - crossings.front()) / (crossings.size() - 1);
    const double closed    = intermediate_axis_flip_time(initial.I, initial.L);
    const double turn      = 2. * M_PI * initial.I[1] / initial.L.norm();
    const double turns     = parameters.end_time / turn;
    const double energy_drift =
      std::abs(last_turn_energy / std::max(1., last_turn_steps) -
               first_turn_energy / std::max(1., first_turn_steps)) / std::max(1., turns - 1.);
    const double momentum_drift = last_momentum_error / turns;
    r.value     = flip_time;
    r.reference = closed;
    r.error     = std::abs(flip_time / closed - 1.);
    r.checks.push_back(check_line("flips", crossings.size() - 1, crossings.size() - 1, 0.));
    std::ostringstream drift;
    drift.precision(3);
    drift << "check: drift_per_turn energy=" << energy_drift
          << " angular_momentum=" << momentum_drift << " bound=1e-08";
    r.checks.push_back(drift.str());
    if (!(energy_drift < 1e-8) || !(momentum_drift < 1e-8))
      r.failure = "the energy or the angular momentum drifts by more than 1e-8 per turn";
    return r;
  }

  std::vector<double> ClumpValidation::state() const
  {
    std::vector<double> s = {double(started), initial.x.x, initial.x.y, initial.x.z,
                             initial.v.x, initial.v.y, initial.v.z, initial.w.x, initial.w.y,
                             initial.w.z, initial.mass, previous_time, previous_L2,
                             first_turn_energy, last_turn_energy, first_turn_steps,
                             last_turn_steps, last_momentum_error};
    for (unsigned int k = 0; k < 4; ++k)
      s.push_back(initial.q[k]);
    for (unsigned int k = 0; k < 3; ++k)
      {
        s.push_back(initial.L[k]);
        s.push_back(initial.I[k]);
      }
    s.insert(s.end(), crossings.begin(), crossings.end());
    return s;
  }

  void ClumpValidation::set_state(const std::vector<double> &s)
  {
    if (s.size() < 28)
      return;
    started       = s[0] != 0.;
    initial.x     = Vec3(s[1], s[2], s[3]);
    initial.v     = Vec3(s[4], s[5], s[6]);
    initial.w     = Vec3(s[7], s[8], s[9]);
    initial.mass  = s[10];
    previous_time = s[11];
    previous_L2   = s[12];
    first_turn_energy = s[13], last_turn_energy = s[14];
    first_turn_steps = s[15], last_turn_steps = s[16], last_momentum_error = s[17];
    for (unsigned int k = 0; k < 4; ++k)
      initial.q[k] = s[18 + k];
    for (unsigned int k = 0; k < 3; ++k)
      {
        initial.L[k] = s[22 + 2 * k];
        initial.I[k] = s[23 + 2 * k];
      }
    crossings.assign(s.begin() + 28, s.end());
  }
} // namespace sluice
