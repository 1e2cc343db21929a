#ifndef mpm_postprocess_energy_balance_h
#define mpm_postprocess_energy_balance_h

#include <mpm/postprocess/postprocessor.h>

#include <string>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The energy budget of a scene without energy sources (no prescribed
     * moving wall): the total energy E = kinetic + strain + gravitational
     * potential may only fall (walls with friction, unilateral contact,
     * damping, plasticity and PIC all dissipate). Reports E - E0 in joules
     * at output times and, at the end, the largest gain max(E - E0) seen at
     * any step and the largest kinetic + strain energy, whose ratio says
     * how much of the energy that moved through the body was created.
     * Unlike the 'conservation' postprocessor's relative energy change,
     * whose scale holds the potential energy (its datum is arbitrary), the
     * gain is an absolute figure: an elastic block resting on a floor
     * oscillates with 2 J while its potential energy is 226 J.
     */
    template <int dim>
    class EnergyBalance : public PostprocessorWithState<dim, EnergyBalance<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &)
      {}

      void
      parse_parameters(ParameterHandler &) override
      {}

      void
      initialize() override;

      void
      execute(const bool output_step) override;

      void
      write_report(std::ostream &report) override;

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &energy0 &max_gain &max_moving_energy &table;
      }

    private:
      double      energy0 = 0, max_gain = 0, max_moving_energy = 0;
      std::string table;
    };
  } // namespace Postprocessors
} // namespace MPM

#endif
