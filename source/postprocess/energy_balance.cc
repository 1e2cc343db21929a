#include <mpm/postprocess/energy_balance.h>
#include <mpm/solver/simulator.h>

#include <iomanip>
#include <sstream>

namespace MPM
{
  namespace Postprocessors
  {
    template <int dim>
    void
    EnergyBalance<dim>::initialize()
    {
      const auto s = this->compute_statistics();
      energy0 =
        s.kinetic_energy + s.strain_energy + s.gravitational_potential_energy;
      max_moving_energy = s.kinetic_energy + s.strain_energy;
    }


    template <int dim>
    void
    EnergyBalance<dim>::execute(const bool output_step)
    {
      const auto   s      = this->compute_statistics();
      const double moving = s.kinetic_energy + s.strain_energy;
      const double gain   = moving + s.gravitational_potential_energy - energy0;
      max_gain            = std::max(max_gain, gain);
      max_moving_energy   = std::max(max_moving_energy, moving);
      if (output_step)
        {
          std::ostringstream line;
          line << std::setw(12) << s.time << std::setw(16) << gain
               << std::setw(16) << moving << '\n';
          table += line.str();
        }
    }


    template <int dim>
    void
    EnergyBalance<dim>::write_report(std::ostream &report)
    {
      const char *unit = dim == 2 ? " J/m" : " J";
      report << "## energy balance: E = kinetic + strain + gravitational "
                "potential, E0 at the start\n"
             << "# time (s)   E - E0 (" << (dim == 2 ? "J/m" : "J")
             << ")   kinetic + strain\n"
             << table << "largest gain max(E - E0) over all steps: "
             << max_gain << unit
             << "\nlargest kinetic + strain energy: " << max_moving_energy
             << unit << "\ngain / largest kinetic + strain: "
             << max_gain / std::max(1e-300, max_moving_energy) << '\n';
    }


    template class EnergyBalance<2>;
    template class EnergyBalance<3>;
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::EnergyBalance,
                           "energy balance",
                           "the energy budget of a scene without energy sources: the largest energy gain against the energy that moved.")
