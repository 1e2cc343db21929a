#include <deal.II/base/symmetric_tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/plugin_registry.h>
#include <mpm/base/units.h>
#include <mpm/materials/drucker_prager.h>
#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

#include <algorithm>
#include <cmath>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * A cohesionless granular skeleton whose friction and dilatancy depend
     * on how far its packing is from the critical one: the dilatancy law of
     * Roux and Radjai (1998) in the form Pailha and Pouliquen (2009) used
     * for submerged granular avalanches,
     *
     *   tan psi = K (phi - phi_c),   mu = tan(phi_c') + tan psi,
     *
     * with phi the solid volume fraction (a state variable, following the
     * skeleton's volume: phi' = phi / (1 + tr(de))), phi_c the critical
     * volume fraction, phi_c' the critical friction angle and K the
     * dilatancy coefficient. A packing denser than critical (phi > phi_c)
     * is stronger and dilates as it shears, until it has loosened to
     * phi_c; a looser one is weaker and contracts (psi < 0) until it has
     * compacted to phi_c. Saturated, the first sucks water in (negative
     * excess pore pressure, more effective stress), the second pushes it
     * out (positive excess pore pressure, less effective stress): the
     * mechanism Rondon, Pouliquen and Aussillous (2011) give for the
     * different collapses of dense and loose submerged columns.
     *
     * The yield surface is the Drucker-Prager cone of the plane-strain fit
     * with the friction angle atan(mu) and the dilation angle psi of the
     * state at the start of the step (explicit in the state), the tension
     * cap at zero mean stress (no cohesion): the return is
     * DruckerPrager::return_to_cone(). A contracting return that would end in
     * tension ends at the apex, zero effective stress: a liquefied skeleton.
     * The dilation slope is bounded so that the cone return's denominator G +
     * K_b eta eta_bar stays above G / 2 (a strongly contracting, weak
     * packing).
     *
     * What it leaves out: the rate dependence of the critical volume
     * fraction (phi_c falls with the inertial or viscous number in
     * Pailha and Pouliquen's model), elasticity that depends on pressure,
     * and any cohesion.
     */
    class CriticalStateDruckerPrager : public MaterialModel
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        IsotropicElasticity::declare_parameters(prm);
        prm.declare_entry("Critical friction angle",
                          "25",
                          Patterns::Double(0, 90),
                          "phi_c' in degrees: the friction angle of the "
                          "packing at its critical volume fraction (steady "
                          "shear without volume change).");
        prm.declare_entry("Critical volume fraction",
                          "0.58",
                          Patterns::Double(0, 1),
                          "phi_c: the solid volume fraction that shearing "
                          "approaches, in (0, 1).");
        prm.declare_entry("Initial volume fraction",
                          "0.58",
                          Patterns::Double(0, 1),
                          "phi_0: the solid volume fraction of the points "
                          "at the start, in (0, 1). For a saturated "
                          "material 1 - its 'Porosity'.");
        prm.declare_entry("Dilatancy coefficient",
                          "4",
                          Patterns::Double(0),
                          "K in tan psi = K (phi - phi_c): how strongly the "
                          "distance from the critical packing sets the "
                          "dilatancy (and the friction mu = tan phi_c' + "
                          "tan psi).");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        elasticity.parse_parameters(prm, "critical state drucker prager");
        critical_friction =
          std::tan(prm.get_double("Critical friction angle") * degree);
        critical_fraction = prm.get_double("Critical volume fraction");
        initial_fraction  = prm.get_double("Initial volume fraction");
        dilatancy         = prm.get_double("Dilatancy coefficient");
        const auto where  = [&](const std::string &entry) {
          return "critical state drucker prager/" + entry + " = " +
                 prm.get(entry);
        };
        check_input(critical_fraction > 0 && critical_fraction < 1,
                    where("Critical volume fraction") +
                      ": must lie in (0, 1).");
        check_input(initial_fraction > 0 && initial_fraction < 1,
                    where("Initial volume fraction") + ": must lie in (0, 1).");
        check_input(prm.get_double("Critical friction angle") > 0 &&
                      prm.get_double("Critical friction angle") < 90,
                    where("Critical friction angle") +
                      ": must lie in (0, 90) degrees.");
        bulk_modulus = elasticity.lambda + 2. / 3. * elasticity.shear_modulus;
      }

      void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double>     &state,
                    const double) const override
      {
        AssertIndexRange(1, state.size());
        const double G = elasticity.shear_modulus;
        // The cone of the packing at the start of the step: the
        // plane-strain fit for the friction mu and the dilatancy tan psi,
        // no cohesion, the cap at zero mean stress (the apex).
        const double tan_psi = dilatancy * (state[1] - critical_fraction);
        DruckerPrager::Cone cone;
        cone.eta = DruckerPrager::plane_strain_slope(
          std::max(0., critical_friction + tan_psi));
        cone.eta_bar = DruckerPrager::plane_strain_slope(tan_psi);
        if (cone.eta > 0)
          cone.eta_bar =
            std::max(cone.eta_bar, -0.5 * G / (bulk_modulus * cone.eta));
        cone.set_multiplier_factor(G, bulk_modulus);

        elasticity.add_stress_increment(strain_increment, stress);
        // The packing follows the skeleton's volume.
        state[1] /= 1 + trace(strain_increment);
        // A contracting return that would end in tension ends at the
        // apex: no effective stress.
        double root_decrease = 0;
        if (DruckerPrager::return_to_cone(
              cone, G, bulk_modulus, stress, root_decrease) !=
            DruckerPrager::Return::elastic)
          state[0] += root_decrease / (std::sqrt(3.) * G);
      }

      double
      strain_energy_density(const SymmetricTensor<2, 3> &stress) const override
      {
        return elasticity.strain_energy_density(stress);
      }

      double
      p_wave_modulus() const override
      {
        return elasticity.p_wave_modulus();
      }

      /// Jaky's K0 = 1 - sin phi with the initial packing's friction.
      double
      default_k0() const override
      {
        const double mu =
          std::max(0.,
                   critical_friction +
                     dilatancy * (initial_fraction - critical_fraction));
        return 1 - std::sin(std::atan(mu));
      }

      unsigned int
      n_state_variables() const override
      {
        return 2;
      }

      std::vector<std::string>
      state_variable_names() const override
      {
        return {"plastic_shear_strain", "volume_fraction"};
      }

      void
      initialize_state(const ArrayView<double> &state) const override
      {
        AssertIndexRange(1, state.size());
        state[0] = 0;
        state[1] = initial_fraction;
      }

    private:
      IsotropicElasticity elasticity;
      double              bulk_modulus      = 0;
      double              critical_friction = 0;
      double              critical_fraction = 0.58;
      double              initial_fraction  = 0.58;
      double              dilatancy         = 4;
    };
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(
  MPM::MaterialModels::CriticalStateDruckerPrager,
  "critical state drucker prager",
  "A cohesionless granular packing whose friction and dilatancy follow its "
  "distance from the critical volume fraction (Roux and Radjai; Pailha and "
  "Pouliquen 2009): dense packings dilate and are stronger, loose ones "
  "contract and are weaker, until sheared to the critical packing.")
