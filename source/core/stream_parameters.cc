// The 'stream' subsection (see the header).

#include <sluice/core/parameter_declaration.h>
#include <sluice/core/scene_parameters.h>
#include <sluice/core/stream_parameters.h>

namespace sluice
{
  using namespace dealii;

  namespace
  {
    StreamRegion region_of(const std::string &s)
    {
      return s == "box" ? StreamRegion::box :
             s == "disc" ? StreamRegion::disc :
             s == "plane" ? StreamRegion::plane :
                            StreamRegion::none;
    }
  } // namespace

  void declare_stream_parameters(ParameterHandler &prm)
  {
    const Patterns::List three(Patterns::Double(), 3, 3, ",");
    prm.enter_subsection("stream");
    declare(prm, "inlet", "none", Patterns::Selection("none|box|disc"),
            "Where a stream's particles are inserted: a box between 'inlet lower corner' and "
            "'inlet upper corner', or a disc (a cylinder of 'inlet radius' and 'inlet "
            "thickness' about 'inlet centre' along 'inlet axis').");
    declare(prm, "inlet lower corner", "0, 0, 0", three, "[m] Box inlet.");
    declare(prm, "inlet upper corner", "0, 0, 0", three, "[m] Box inlet.");
    declare(prm, "inlet centre", "0, 0, 0", three, "[m] Disc inlet.");
    declare(prm, "inlet axis", "0, 0, 1", three, "[-] Disc inlet: its normal.");
    declare(prm, "inlet radius", "0", Patterns::Double(0.), "[m] Disc inlet.");
    declare(prm, "inlet thickness", "0", Patterns::Double(0.),
            "[m] Disc inlet: extent along the axis (at least a diameter).");
    declare(prm, "rate", "0", Patterns::Double(0.), "[1/s] Particles inserted per second.");
    declare(prm, "mass rate", "0", Patterns::Double(0.),
            "[kg/s] Mass inserted per second (replaces 'rate' when > 0, by the mean mass of "
            "the size distribution).");
    declare(prm, "radius", "0.001", Patterns::Double(0.), "[m] Radius of the stream's spheres.",
            "(0, inf)");
    declare(prm, "radius max", "0", Patterns::Double(0.),
            "[m] If above 'radius': radii uniform between the two.");
    declare(prm, "type", "0", Patterns::Integer(0), "Material type of the stream's spheres.",
            "a material type");
    declare(prm, "velocity", "0, 0, 0", three, "[m/s] Velocity of an inserted sphere.");
    declare(prm, "start time", "0", Patterns::Double(0.), "[s] Insertion starts.");
    declare(prm, "end time", "1e300", Patterns::Double(0.), "[s] Insertion ends.");
    declare(prm, "interval", "0.001", Patterns::Double(0.),
            "[s] Time between insertion batches (and outlet checks).", "(0, inf)");
    declare(prm, "outlet", "none", Patterns::Selection("none|box|plane"),
            "Where particles leave and are counted: a box between 'outlet lower corner' and "
            "'outlet upper corner', or the half-space behind the plane through 'outlet point' "
            "against 'outlet normal'.");
    declare(prm, "outlet lower corner", "0, 0, 0", three, "[m] Box outlet.");
    declare(prm, "outlet upper corner", "0, 0, 0", three, "[m] Box outlet.");
    declare(prm, "outlet point", "0, 0, 0", three, "[m] Plane outlet.");
    declare(prm, "outlet normal", "0, 0, 1", three,
            "[-] Plane outlet: points into the domain; centres behind it leave.");
    declare(prm, "recycle", "false", Patterns::Bool(),
            "A particle leaving through the outlet re-enters at the inlet (same id, radius "
            "and type, the inlet's velocity), in addition to 'rate'.");
    declare(prm, "seed", "1", Patterns::Integer(0), "Seed of the insertion positions.");
    prm.leave_subsection();
  }

  StreamParameters read_stream_parameters(ParameterHandler &prm, const std::string &scene,
                                          const unsigned int n_materials)
  {
    StreamParameters s;
    const auto       fail = [&](const std::string &entry, const std::string &what) {
      throw InputError("error in '" + scene + "': entry 'stream/" + entry + "' " + what);
    };
    prm.enter_subsection("stream");
    s.inlet           = region_of(prm.get("inlet"));
    s.inlet_lower     = get_vector(prm, "inlet lower corner");
    s.inlet_upper     = get_vector(prm, "inlet upper corner");
    s.inlet_centre    = get_vector(prm, "inlet centre");
    s.inlet_axis      = get_vector(prm, "inlet axis");
    s.inlet_radius    = prm.get_double("inlet radius");
    s.inlet_thickness = prm.get_double("inlet thickness");
    s.rate            = prm.get_double("rate");
    s.mass_rate       = prm.get_double("mass rate");
    s.radius          = prm.get_double("radius");
    s.radius_max      = prm.get_double("radius max");
    s.type            = prm.get_integer("type");
    s.velocity        = get_vector(prm, "velocity");
    s.start_time      = prm.get_double("start time");
    s.end_time        = prm.get_double("end time");
    s.interval        = prm.get_double("interval");
    s.outlet          = region_of(prm.get("outlet"));
    s.outlet_lower    = get_vector(prm, "outlet lower corner");
    s.outlet_upper    = get_vector(prm, "outlet upper corner");
    s.outlet_point    = get_vector(prm, "outlet point");
    s.outlet_normal   = get_vector(prm, "outlet normal");
    s.recycle         = prm.get_bool("recycle");
    s.seed            = prm.get_integer("seed");
    prm.leave_subsection();
    if (!(s.radius > 0.))
      fail("radius", "= 0 is outside the allowed range (0, inf)");
    if (!(s.interval > 0.))
      fail("interval", "= 0 is outside the allowed range (0, inf)");
    if (s.type >= n_materials)
      fail("type", "= " + std::to_string(s.type) + " is outside the allowed range: material "
                     "types 0.." + std::to_string(n_materials - 1));
    const double d_max = 2. * std::max(s.radius, s.radius_max);
    if (s.inlet == StreamRegion::box)
      for (unsigned int d = 0; d < 3; ++d)
        if (!(s.inlet_upper[d] - s.inlet_lower[d] >= d_max))
          fail("inlet upper corner", "must be at least a diameter above 'inlet lower corner' "
                                     "in every direction");
    if (s.inlet == StreamRegion::disc)
      {
        if (!(norm(s.inlet_axis) > 0.))
          fail("inlet axis", "is the zero vector");
        s.inlet_axis = (1. / norm(s.inlet_axis)) * s.inlet_axis;
        if (!(s.inlet_thickness >= d_max) || !(s.inlet_radius >= 0.5 * d_max))
          fail("inlet thickness", "and 'inlet radius' must hold a sphere (a diameter and a radius)");
      }
    if (s.outlet == StreamRegion::plane)
      {
        if (!(norm(s.outlet_normal) > 0.))
          fail("outlet normal", "is the zero vector");
        s.outlet_normal = (1. / norm(s.outlet_normal)) * s.outlet_normal;
      }
    if (s.recycle && (s.inlet == StreamRegion::none || s.outlet == StreamRegion::none))
      fail("recycle", "needs an inlet and an outlet");
    if (s.inlet != StreamRegion::none && !(s.rate > 0. || s.mass_rate > 0. || s.recycle))
      fail("rate", "and 'mass rate' are 0: an inlet needs a rate (or 'recycle')");
    return s;
  }
} // namespace sluice
