#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/basal_law.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The travel angle (Heim's "Fahrboeschung") of a moving mass: the
     * slope of its energy line from the start, measured at its centre of
     * mass,
     *
     *   H / L = (drop + v_0^2 / 2g - v^2 / 2g) / horizontal travel,
     *
     * with v^2 / 2g the mean velocity head (kinetic energy over weight).
     * A rigid body sliding on a plane with Coulomb friction mu loses
     * exactly mu g cos(theta) per metre along the slope, mu g per metre
     * of horizontal travel: H / L = mu at every time, and at rest the
     * centre of mass stands where the angle atan(mu) from its start (and
     * its initial velocity head) says. Curvature of the path (the normal
     * force rises where the path turns up), internal dissipation and
     * spreading make H / L of a real mass larger; hazard practice reads
     * runouts from it (Heim 1932; Hsu 1975). Reports the energy line's
     * slope at output times and at the end, beside the bed's mu when a
     * frictional 'Bed boundary' is named. Distances along gravity and
     * normal to it: any orientation of the scene.
     */
    template <int dim>
    class TravelAngle : public PostprocessorWithState<dim, TravelAngle<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Bed boundary",
                          "",
                          Patterns::Anything(),
                          "Name of a frictional boundary (from 'Boundary "
                          "conditions/List of boundaries') whose friction "
                          "coefficient mu the travel angle is compared with; "
                          "empty: no comparison.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        bed = prm.get("Bed boundary");
      }

      void
      initialize() override
      {
        if (!bed.empty())
          {
            const BasalLaw<dim> *law =
              this->get_boundary_conditions().basal_law(bed);
            check_input(law != nullptr,
                        "Postprocess/travel angle/Bed boundary = '" + bed +
                          "' is not a frictional boundary of 'Boundary "
                          "conditions/List of boundaries'.");
            mu = law->friction_coefficient();
          }
        const auto s = this->compute_statistics();
        x0           = s.centre_of_mass;
        head0        = velocity_head(s);
      }

      void
      execute(const bool output_step) override
      {
        if (!output_step)
          return;
        const auto s              = this->compute_statistics();
        const auto [drop, travel] = drop_and_travel(s);
        const double head         = velocity_head(s);
        last_ratio        = travel > 0 ? (drop + head0 - head) / travel : 0;
        last_drop         = drop;
        last_travel       = travel;
        last_head         = head;
        std::ostringstream line;
        line << std::setw(10) << s.time << std::setw(14) << travel
             << std::setw(14) << drop << std::setw(14) << head
             << std::setw(14) << last_ratio << '\n';
        table += line.str();
      }

      void
      write_report(std::ostream &report) override
      {
        report << "## travel angle: energy line of the centre of mass, "
                  "H / L = (drop + v0^2/2g - v^2/2g) / horizontal travel\n"
               << "# time (s)  travel L (m)  drop (m)  v^2/2g (m)  H / L\n"
               << table << "initial velocity head v0^2/2g (m): " << head0
               // One quantity a line, so that scripts/convergence.py
               // follows each under refinement.
               << "\nhorizontal travel L at the end (m): " << last_travel
               << "\ndrop at the end (m): " << last_drop
               << "\nvelocity head v^2/2g at the end (m): " << last_head
               << "\nH / L at the end: " << last_ratio
               << "\ntravel angle at the end (deg): "
               << std::atan(last_ratio) * 180 / M_PI << '\n';
        if (mu >= 0)
          report << "bed friction coefficient mu: " << mu
                 << " (angle " << std::atan(mu) * 180 / M_PI
                 << " deg)\n(H / L) / mu - 1: " << last_ratio / mu - 1
                 << '\n';
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & x0 & head0 & mu & table & last_ratio & last_drop & last_travel &
          last_head;
      }

    private:
      /// Kinetic energy over weight (m).
      double
      velocity_head(const GlobalStatistics<dim> &s) const
      {
        const double g = this->get_time_stepping().gravity.norm();
        return s.mass > 0 && g > 0 ? s.kinetic_energy / (s.mass * g) : 0;
      }

      /// The centre of mass's drop along gravity and its travel normal to
      /// it since the start.
      std::pair<double, double>
      drop_and_travel(const GlobalStatistics<dim> &s) const
      {
        Tensor<1, dim> g_unit = this->get_time_stepping().gravity;
        check_input(g_unit.norm() > 0,
                    "Postprocess/List of postprocessors: 'travel angle' "
                    "needs gravity (Time stepping/Gravity).");
        g_unit /= g_unit.norm();
        const Tensor<1, dim> dx   = s.centre_of_mass - x0;
        const double         drop = dx * g_unit;
        return {drop, (dx - drop * g_unit).norm()};
      }

      std::string    bed;
      Tensor<1, dim> x0;
      double         head0 = 0, mu = -1;
      double         last_ratio = 0, last_drop = 0, last_travel = 0,
             last_head = 0;
      std::string table;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::TravelAngle,
                           "travel angle",
                           "the slope of the centre of mass's energy line (Heim's travel angle, H/L) against the bed's friction coefficient.")
