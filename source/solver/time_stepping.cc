#include <deal.II/base/utilities.h>

#include <mpm/base/function_input.h>
#include <mpm/base/input_error.h>
#include <mpm/base/plugin_registry.h>
#include <mpm/solver/time_stepping.h>

#include <sstream>

namespace MPM
{
  template <int dim>
  void
  TimeSteppingParameters<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    {
      prm.declare_entry("End time",
                        "1",
                        Patterns::Double(0),
                        "Simulated time at which the run stops, in s.");
      prm.declare_entry("Time step selection",
                        "cfl",
                        Patterns::Selection("cfl|fixed"),
                        "'cfl': dt = CFL number * h_min / (c + |v|_max) with "
                        "c the largest elastic P-wave speed, h_min the "
                        "shortest edge of the cells that hold points and "
                        "|v|_max the largest "
                        "point speed, recomputed every step; 'fixed': 'Time "
                        "step'.");
      prm.declare_entry("Time step",
                        "1e-4",
                        Patterns::Double(0),
                        "Fixed time step in s (Time step selection = "
                        "fixed); must be > 0.");
      prm.declare_entry("CFL number",
                        "0.5",
                        Patterns::Double(0),
                        "Courant number of the adaptive step, in (0, 1].");
      prm.declare_entry("Maximum time step",
                        "1e100",
                        Patterns::Double(0),
                        "Upper bound of the adaptive time step, in s.");
      prm.declare_entry("Update scheme",
                        "MUSL",
                        Patterns::Selection(StepSchemeRegistry::names()),
                        "When the stress is updated, the order of a step's "
                        "operations (source/solver/step_schemes/). " +
                          StepSchemeRegistry::descriptions());
      prm.declare_entry("Local damping",
                        "0",
                        Patterns::Anything(),
                        "Cundall's local non-viscous damping coefficient "
                        "alpha in [0, 1): the nodal force is reduced by "
                        "alpha |f| in the direction of the nodal velocity. "
                        "For quasi-static problems (settling under gravity, "
                        "strength reduction); 0 for dynamics. A number or a "
                        "function of time t (s), e.g. '0.8 * (t < 2)' to "
                        "settle a slope for 2 s and then release it.");
      prm.declare_entry(
        "Volumetric strain averaging",
        "cell",
        Patterns::Selection("none|cell|patch"),
        "'cell' (default): each point's volumetric strain rate (the trace "
        "of its velocity gradient) is replaced by the volume-weighted mean "
        "over the points of its cell before the stress and volume update, "
        "the deviatoric part kept (an F-bar-type anti-locking: plastically "
        "incompressible flow with several points per cell locks without "
        "it, and granular runouts then move with the mesh; "
        "doc/convergence.md). 'patch': the cells' means averaged again, "
        "each vertex taking the volume-weighted mean of the cells around "
        "it and each cell the mean of its vertices: a smoother volumetric "
        "rate, with less of the point-to-point stress noise that a "
        "cohesionless skeleton turns into dilation at its apex (the "
        "saturated flume's suction; doc/pore_water.md, 'A saturated flume "
        "beyond 0.1 s'). The forces take each point's own stress. "
        "With a FLIP share ('Transfer/Scheme = flip/pic blend', 'FLIP "
        "fraction' > 0) it was measured to create energy once the material "
        "flows (an elastic wedge down the flume, a dilating slope; mpm "
        "warns): use 'none' there. 'none': each point's own rate.");
      prm.declare_entry("Gravity",
                        dim == 2 ? "0, -9.81" : "0, 0, -9.81",
                        Patterns::List(Patterns::Double(), dim, dim),
                        "Gravitational acceleration vector in m/s^2.");
    }
    prm.leave_subsection();
  }


  template <int dim>
  void
  TimeSteppingParameters<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    {
      end_time          = prm.get_double("End time");
      adaptive          = select_choice<bool>(prm.get("Time step selection"),
                                     {{"cfl", true}, {"fixed", false}},
                                     "Time stepping/Time step selection");
      fixed_time_step   = prm.get_double("Time step");
      cfl_number        = prm.get_double("CFL number");
      maximum_time_step = prm.get_double("Maximum time step");
      step_scheme = StepSchemeRegistry::create(prm.get("Update scheme"),
                                               "Time stepping/Update scheme",
                                               prm);
      const std::string damping = prm.get("Local damping");
      local_damping_function.reset();
      try
        {
          local_damping = Utilities::string_to_double(damping);
        }
      catch (...)
        {
          auto function = std::make_shared<FunctionParser<1>>(1);
          parse_function_or_throw("Time stepping/Local damping = '" + damping +
                                    "'",
                                  [&]() {
                                    function->initialize("t", damping, {});
                                    function->value(Point<1>());
                                  });
          local_damping_function = function;
          local_damping          = function->value(Point<1>());
        }
      local_damping_expression = damping;
      check_local_damping(local_damping, 0);
      volumetric_strain_averaging = select_choice<VolumetricStrainAveraging>(
        prm.get("Volumetric strain averaging"),
        {{"none", VolumetricStrainAveraging::none},
         {"cell", VolumetricStrainAveraging::cell},
         {"patch", VolumetricStrainAveraging::patch}},
        "Time stepping/Volumetric strain averaging");
      const auto g  = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("Gravity")));
      for (unsigned int d = 0; d < dim; ++d)
        scene_gravity[d] = g[d];
    }
    prm.leave_subsection();
    check_input(adaptive || fixed_time_step > 0,
                "Time stepping/Time step must be > 0.");
    check_input(!adaptive || (cfl_number > 0 && cfl_number <= 1),
                "Time stepping/CFL number = " + std::to_string(cfl_number) +
                  ": must lie in (0, 1].");
  }


  template <int dim>
  double
  TimeSteppingParameters<dim>::local_damping_at(const double time) const
  {
    if (!local_damping_function)
      return local_damping;
    const double alpha = local_damping_function->value(Point<1>(time));
    check_local_damping(alpha, time);
    return alpha;
  }


  template <int dim>
  void
  TimeSteppingParameters<dim>::check_local_damping(const double alpha,
                                                   const double time) const
  {
    if (!(alpha >= 0 && alpha < 1))
      {
        std::ostringstream message;
        message << "Time stepping/Local damping = '"
                << local_damping_expression << "' is " << alpha
                << " at t = " << time << " s: it must lie in [0, 1).";
        throw InputError(message.str());
      }
  }


  template struct TimeSteppingParameters<2>;
  template struct TimeSteppingParameters<3>;
} // namespace MPM
