#pragma once
// The 'stream' subsection: particles inserted at a rate through an inlet
// region, removed at an outlet and counted, optionally recycled from the
// outlet to the inlet (dem/particle_stream.h, doc/geometry.md).

#include <sluice/core/vector3.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sluice
{
  enum class StreamRegion
  {
    none,
    box,  // between two corners
    disc, // a cylinder of 'radius' and 'thickness' about 'centre' along 'axis'
    plane // outlet only: the half-space behind a plane
  };

  struct StreamParameters
  {
    StreamRegion inlet = StreamRegion::none, outlet = StreamRegion::none;
    Vec3         inlet_lower, inlet_upper, inlet_centre, inlet_axis{0., 0., 1.};
    double       inlet_radius = 0., inlet_thickness = 0.;
    Vec3         outlet_lower, outlet_upper, outlet_point, outlet_normal{0., 0., 1.};
    double       rate = 0.;      // [1/s]
    double       mass_rate = 0.; // [kg/s], used if > 0
    double       radius = 0.001, radius_max = 0.; // [m]; > radius: uniform in between
    unsigned int type   = 0;
    Vec3         velocity; // [m/s]
    double       start_time = 0., end_time = 1e300; // [s]
    double       interval   = 1e-3;                 // [s] between batches
    bool         recycle    = false;
    unsigned int seed       = 1;

    bool any() const { return inlet != StreamRegion::none || outlet != StreamRegion::none; }
  };

  void declare_stream_parameters(dealii::ParameterHandler &prm);
  /// Throws InputError naming the entry.
  StreamParameters read_stream_parameters(dealii::ParameterHandler &prm, const std::string &scene,
                                          unsigned int n_materials);
} // namespace sluice
