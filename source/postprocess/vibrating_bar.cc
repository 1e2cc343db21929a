#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The 1D-like vibrating elastic bar (Bardenhagen 2002): a bar of length
     * L along x, fixed at x = 0, free at x = L, started with the first mode's
     * velocity v0 sin(beta x), beta = pi / (2 L). Its centre-of-mass
     * velocity is v_cm(t) = (2 v0 / pi) cos(omega t) with omega = beta
     * sqrt(E / rho). Reports v_cm against that at output times, the largest
     * deviation relative to 2 v0 / pi, and the period measured from the
     * zero crossings of v_cm against 2 pi / omega. The wave speed is that
     * of the first material, which must have nu = 0.
     */
    template <int dim>
    class VibratingBar : public PostprocessorWithState<dim, VibratingBar<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Bar length", "25", Patterns::Double(0), "L in m.");
        prm.declare_entry("Velocity amplitude",
                          "0.1",
                          Patterns::Double(0),
                          "v0 in m/s.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        length = prm.get_double("Bar length");
        v0     = prm.get_double("Velocity amplitude");
      }

      void
      initialize() override
      {
        // With nu = 0 the P-wave speed sqrt((lambda + 2 mu) / rho) is the
        // bar speed sqrt(E / rho).
        omega = M_PI / (2 * length) * this->get_materials()[0].wave_speed();
        amplitude        = 2 * v0 / M_PI;
      }

      void
      execute(const bool output_step) override
      {
        const auto   s     = this->compute_statistics();
        const double v     = s.mean_velocity[0];
        const double exact = amplitude * std::cos(omega * s.time);
        max_error = std::max(max_error, std::abs(v - exact) / amplitude);
        if (last_time >= 0 && (last_v > 0) != (v > 0))
          crossings.push_back(last_time +
                              (s.time - last_time) * last_v / (last_v - v));
        last_time = s.time;
        last_v    = v;
        if (output_step)
          {
            std::ostringstream line;
            line << std::setw(12) << s.time << std::setw(14) << v
                 << std::setw(14) << exact << std::setw(14)
                 << (v - exact) / amplitude << '\n';
            table += line.str();
          }
      }

      void
      write_report(std::ostream &report) override
      {
        const double period = 2 * M_PI / omega;
        report << "## vibrating bar: centre-of-mass velocity against "
                  "(2 v0/pi) cos(omega t)\n"
               << "# time (s)   v_cm mpm (m/s)  v_cm exact (m/s)  error / "
                  "(2 v0/pi)\n"
               << table;
        report << "max |v_cm error| / (2 v0/pi): " << max_error << '\n';
        if (crossings.size() >= 2)
          {
            const double measured = 2 * (crossings[1] - crossings[0]);
            report << "period mpm (s): " << measured
                   << "\nperiod exact (s): " << period
                   << "\nperiod relative error: "
                   << (measured - period) / period << '\n';
          }
        else
          report << "period: fewer than two zero crossings of v_cm\n";
      }

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & omega & amplitude & max_error & last_time & last_v & crossings & table;
      }

    private:
      double              length = 25, v0 = 0.1;
      double              omega = 1, amplitude = 1;
      double              max_error = 0, last_time = -1, last_v = 0;
      std::vector<double> crossings;
      std::string         table;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::VibratingBar,
                           "vibrating bar",
                           "the vibrating elastic bar (Bardenhagen 2002) against its first mode.")
