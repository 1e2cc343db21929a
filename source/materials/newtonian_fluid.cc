#include <deal.II/base/symmetric_tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/materials/material_model.h>

#include <algorithm>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * A weakly compressible Newtonian liquid (water as a phase of its own:
     * a dam break, a flood wave): sigma = -p I + 2 eta dev(D), with the
     * pressure from the volume change, dp = -K tr(de), and D = de / dt the
     * rate of deformation. The pressure is the state: it is -tr(sigma) / 3
     * of the point's stress, so the model keeps no state variable. With
     * 'Tension cutoff' the pressure stays >= 0: a liquid's free surface
     * does not pull, and spray leaves as it would.
     *
     * K sets the sound speed sqrt(K / rho) and with it the time step: a
     * real liquid's K (2.2e9 Pa for water) is not needed where the flow is
     * much slower than sound; the usual choice in weakly compressible
     * methods is a sound speed ten times the largest flow speed, which
     * keeps the density within 1 % of its rest value.
     */
    class NewtonianFluid : public MaterialModel
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Bulk modulus",
                          "2.2e9",
                          Patterns::Double(0),
                          "K in Pa: the pressure rises by K times the "
                          "relative volume lost; the sound speed is "
                          "sqrt(K / rho). Must be > 0.");
        prm.declare_entry("Viscosity",
                          "1e-3",
                          Patterns::Double(0),
                          "Dynamic viscosity eta in Pa s (water: 1e-3).");
        prm.declare_entry("Tension cutoff",
                          "true",
                          Patterns::Bool(),
                          "Keep the pressure >= 0 (a liquid does not "
                          "sustain tension).");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        bulk_modulus   = prm.get_double("Bulk modulus");
        viscosity      = prm.get_double("Viscosity");
        tension_cutoff = prm.get_bool("Tension cutoff");
        check_input(bulk_modulus > 0,
                    "newtonian fluid/Bulk modulus = " +
                      prm.get("Bulk modulus") + ": must be > 0 (Pa).");
      }

      void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double> &,
                    const double time_step) const override
      {
        double p = -trace(stress) / 3 - bulk_modulus * trace(strain_increment);
        if (tension_cutoff)
          p = std::max(p, 0.);
        stress = -p * unit_symmetric_tensor<3>();
        if (time_step > 0)
          stress += (2 * viscosity / time_step) * deviator(strain_increment);
      }

      double
      strain_energy_density(const SymmetricTensor<2, 3> &stress) const override
      {
        const double p = -trace(stress) / 3;
        return p * p / (2 * bulk_modulus);
      }

      double
      p_wave_modulus() const override
      {
        return bulk_modulus;
      }

      /// A liquid at rest: the same pressure in every direction.
      double
      default_k0() const override
      {
        return 1;
      }

    private:
      double bulk_modulus   = 2.2e9;
      double viscosity      = 1e-3;
      bool   tension_cutoff = true;
    };
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(MPM::MaterialModels::NewtonianFluid,
                            "newtonian fluid",
                            "A weakly compressible Newtonian liquid: pressure "
                            "from the volume change, viscous deviatoric "
                            "stress (a dam break).")
