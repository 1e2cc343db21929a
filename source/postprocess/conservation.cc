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
     * Conservation of mass and momentum: mass must stay exactly constant
     * and the momentum change must equal the impulse of gravity, M g t (no
     * boundary forces act on a free-falling body). Reports both errors at
     * output times and their maxima over the run, and the relative change
     * of total energy (kinetic + strain + gravitational).
     */
    template <int dim>
    class Conservation : public PostprocessorWithState<dim, Conservation<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &)
      {}

      void
      initialize() override
      {
        const auto s = this->compute_statistics();
        mass0        = s.mass;
        momentum0    = s.momentum;
        // sum_p m_p |v_p| would be the natural scale without gravity; the
        // statistics hold M times the mean speed, the same for a body in
        // uniform motion, and not zero for bodies colliding head-on.
        momentum_scale0 = s.mass * s.mean_speed;
        energy0 =
          s.kinetic_energy + s.strain_energy + s.gravitational_potential_energy;
        time0 = s.time;
        const auto spin =
          this->spin_angular_momentum(Point<dim>(s.centre_of_mass),
                                      s.mean_velocity);
        angular_momentum0 = spin.first;
        angular_momentum_scale0 = spin.second;
      }

      /// @p error / @p scale, 0 where both are 0 (nothing moved).
      static double
      relative(const double error, const double scale)
      {
        return error == 0 ? 0. : error / std::max(1e-300, scale);
      }

      void
      execute(const bool output_step) override
      {
        const auto           s          = this->compute_statistics();
        const auto           g          = this->get_time_stepping().gravity;
        const double   t = s.time - time0;
        const Tensor<1, dim> expected = momentum0 + mass0 * g * t;
        const double mass_error = std::abs(s.mass - mass0) / mass0;
        // Relative to the impulse of gravity, or without gravity to the
        // initial momentum scale M |v|_mean.
        // A scene at rest without gravity (set moving by a boundary) has
        // neither: then the present motion's M |v|_mean and kinetic +
        // strain energy are the scales (0 where nothing moves yet).
        const double momentum_scale =
          g.norm() > 0 ?
            mass0 * g.norm() * t :
            (momentum_scale0 > 0 ? momentum_scale0 : s.mass * s.mean_speed);
        const double momentum_error =
          relative((s.momentum - expected).norm(), momentum_scale);
        const double energy = s.kinetic_energy + s.strain_energy +
                              s.gravitational_potential_energy;
        double energy_scale =
          std::max(std::abs(energy0), mass0 * g.norm() * g.norm() * t * t / 2);
        if (!(energy_scale > 0))
          energy_scale = s.kinetic_energy + s.strain_energy;
        const double energy_change =
          energy - energy0 == 0 ?
            0. :
            (energy - energy0) / std::max(1e-300, energy_scale);
        max_mass_error     = std::max(max_mass_error, mass_error);
        max_momentum_error = std::max(max_momentum_error, momentum_error);
        max_energy_change  = std::max(max_energy_change, std::abs(energy_change));
        // Spin: angular momentum about the moving centre of mass, which
        // uniform gravity does not change.
        const auto spin =
          this->spin_angular_momentum(Point<dim>(s.centre_of_mass),
                                      s.mean_velocity);
        const double angular_momentum_error =
          (spin.first - angular_momentum0).norm() /
          std::max({1e-300, angular_momentum_scale0, spin.second});
        max_angular_momentum_error =
          std::max(max_angular_momentum_error, angular_momentum_error);
        if (output_step)
          {
            std::ostringstream line;
            line << std::setw(12) << s.time << std::setw(14) << mass_error
                 << std::setw(14) << momentum_error << std::setw(14)
                 << energy_change << std::setw(14) << angular_momentum_error
                 << '\n';
            table += line.str();
          }
      }

      void
      write_report(std::ostream &report) override
      {
        report << "## conservation: mass and momentum against M0 and p0 + M0 "
                  "g t\n"
               << "# time (s)   |M - M0|/M0  |p - p0 - M0 g t|/(M0 g t, or M0 |v|_mean,0 if g = 0)  "
                  "energy change / max(|E0|, M0 g^2 t^2 / 2)  |L - L0| / "
                  "sum m |x - x_c| |v| (at t0, or now if larger; L about the centre of "
                  "mass x_c)\n"
               << table << "max mass error: " << max_mass_error
               << "\nmax momentum error: " << max_momentum_error
               << "\nmax energy change: " << max_energy_change
               << "\nmax angular momentum error: " << max_angular_momentum_error
               << '\n';
      }

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & mass0 & energy0 & time0 & momentum0 & momentum_scale0 & max_mass_error & max_momentum_error & max_energy_change & table &
          angular_momentum0 & angular_momentum_scale0 &
          max_angular_momentum_error;
      }

    private:
      double             mass0 = 0, energy0 = 0, time0 = 0;
      Tensor<1, dim>     momentum0;
      double             momentum_scale0 = 0;
      double             max_mass_error = 0, max_momentum_error = 0,
                         max_energy_change = 0;
      Tensor<1, 3>       angular_momentum0;
      double             angular_momentum_scale0    = 0;
      double             max_angular_momentum_error = 0;
      std::string        table;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::Conservation,
                           "conservation",
                           "mass, momentum, energy and angular momentum against their start.")
