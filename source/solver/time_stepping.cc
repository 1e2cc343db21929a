#include <deal.II/base/utilities.h>

#include <mpm/base/input_error.h>
#include <mpm/base/plugin_registry.h>
#include <mpm/solver/time_stepping.h>

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
                        "USF",
                        Patterns::Selection("USF|USL|MUSL"),
                        "When the stress is updated: USF (Update Stress "
                        "First, before the nodal momentum update), USL "
                        "(Update Stress Last), MUSL (Modified USL).");
      prm.declare_entry("Local damping",
                        "0",
                        Patterns::Double(0, 1),
                        "Cundall's local non-viscous damping coefficient "
                        "alpha: the nodal force is reduced by alpha |f| in "
                        "the direction of the nodal velocity. For quasi-"
                        "static problems (e.g. settling under gravity); 0 "
                        "for dynamics.");
      prm.declare_entry(
        "Volumetric strain averaging",
        "none",
        Patterns::Selection("none|cell"),
        "'cell': each point's volumetric strain rate (the trace of its "
        "velocity gradient) is replaced by the volume-weighted mean over "
        "the points of its cell before the stress and volume update, the "
        "deviatoric part kept (an F-bar-type anti-locking for plastically "
        "incompressible flow with several points per cell; "
        "doc/convergence.md). 'none': each point's own.");
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
      scheme = select_choice<UpdateScheme>(prm.get("Update scheme"),
                                           {{"USF", UpdateScheme::usf},
                                            {"USL", UpdateScheme::usl},
                                            {"MUSL", UpdateScheme::musl}},
                                           "Time stepping/Update scheme");
      local_damping = prm.get_double("Local damping");
      average_volumetric_strain =
        select_choice<bool>(prm.get("Volumetric strain averaging"),
                            {{"none", false}, {"cell", true}},
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


  template struct TimeSteppingParameters<2>;
  template struct TimeSteppingParameters<3>;
} // namespace MPM
