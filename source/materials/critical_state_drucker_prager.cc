#include <deal.II/base/symmetric_tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/plugin_registry.h>
#include <mpm/base/units.h>
#include <mpm/materials/drucker_prager.h>
#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

#include <algorithm>
#include <cmath>
#include <utility>

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
     * 'Fluid viscosity' eta_f > 0 adds the viscous shear stress of a dense
     * suspension (Boyer, Guazzelli and Pouliquen 2011) at the packing's
     * volume fraction, 2 eta_f eta_r(phi) D' with D' the deviatoric
     * strain rate, and its particle pressure p' = tau / mu(J) ('Shear-induced
     * pressure'); at the viscous number J = (phi_c / phi - 1)^2 of
     * their phi(J) = phi_c / (1 + J^1/2) (phi_c in place of their phi_m),
     * eta_r = mu(J) / J with mu(J) = tan(phi_c') + J + 5/2 phi_c J^1/2
     * (their mu_2 term left out), at most 'Maximum viscosity ratio'
     * (which it also is for phi >= phi_c). Why: at the apex, a liquefied
     * packing carries no effective stress, and without it a liquefied
     * submerged column runs as an inviscid liquid, at the speed of its
     * buoyant weight (doc/pore_water.md, "A submerged collapse"); the
     * viscosity alone slows it, the particle pressure (which gives the
     * layer friction and draws water in as it shears) makes its runout
     * agree within 3 % on 5, 2.5 and 1.25 mm cells (its 95 % point moves by
     * 1.0 % and then 2.6 %: not shown converged). The viscous part is not
     * accumulated: it is kept in six state variables and replaced every step.
     * Its energy is not in the strain energy.
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
        prm.declare_entry(
          "Fluid viscosity",
          "0",
          Patterns::Double(0),
          "eta_f in Pa s, >= 0: the viscosity of the liquid between the "
          "grains. Above 0 the skeleton carries a dense suspension's viscous "
          "shear stress 2 eta_f eta_r(phi) D' (Boyer, Guazzelli and "
          "Pouliquen 2011: eta_r = mu(J) / J at J = (phi_c / phi - 1)^2, "
          "mu(J) = tan phi_c' + J + 5/2 phi_c J^1/2), which a liquefied "
          "packing (no effective stress) keeps; 0: rate-independent.");
        prm.declare_entry(
          "Shear-induced pressure",
          "true",
          Patterns::Bool(),
          "With a 'Fluid viscosity': whether the sheared suspension also "
          "carries its particle pressure p' = tau / mu(J) (Boyer et al. "
          "2011: eta_f gamma_dot / J below the cap), as an isotropic "
          "compression of the skeleton. It gives a liquefied layer "
          "friction and draws water in as it shears: with it the loose "
          "submerged collapse runs out 2.53 / 2.58 / 2.50 L0 on 5 / 2.5 / "
          "1.25 mm (95 % of the volume 2.15 / 2.13 / 2.07 L0: within 3 %, "
          "not shown converged), without it the "
          "runout grows by a third per "
          "halving of the cells (doc/pore_water.md, 'A submerged "
          "collapse').");
        prm.declare_entry(
          "Maximum viscosity ratio",
          "1000",
          Patterns::Double(1),
          "The largest eta_r (the suspension's viscosity over the "
          "liquid's, which diverges as phi approaches phi_c; also taken for "
          "phi >= phi_c, where the contacts' friction carries the shear). "
          "It sets the time step's viscous bound dt <= rho h^2 / (2 d "
          "eta_f eta_r).");
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
        fluid_viscosity = prm.get_double("Fluid viscosity");
        maximum_ratio   = prm.get_double("Maximum viscosity ratio");
        shear_induced_pressure = prm.get_bool("Shear-induced pressure");
        bulk_modulus = elasticity.lambda + 2. / 3. * elasticity.shear_modulus;
      }

      void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double>     &state,
                    const double                 time_step) const override
      {
        AssertIndexRange(n_state_variables() - 1, state.size());
        if (fluid_viscosity > 0)
          stress -= viscous_stress(state);
        update_contact_stress(strain_increment, stress, state);
        if (fluid_viscosity > 0 && time_step > 0)
          {
            const auto [ratio, mu] = suspension(state[1]);
            const SymmetricTensor<2, 3> rate =
              deviator(strain_increment) / time_step;
            SymmetricTensor<2, 3> viscous =
              (2 * fluid_viscosity * ratio) * rate;
            if (shear_induced_pressure)
              // p' = tau / mu(J): Boyer et al.'s friction law between the
              // suspension's shear stress and its particle pressure.
              viscous -=
                (fluid_viscosity * ratio * std::sqrt(2 * (rate * rate)) / mu) *
                unit_symmetric_tensor<3>();
            for (unsigned int c = 0; c < 6; ++c)
              state[2 + c] =
                viscous[SymmetricTensor<2, 3>::unrolled_to_component_indices(
                  c)];
            stress += viscous;
          }
      }

      double
      maximum_viscosity() const override
      {
        return fluid_viscosity * maximum_ratio;
      }

    private:
      /**
       * The suspension at volume fraction @p phi: its viscosity ratio
       * eta_r = mu(J) / J (at most the 'Maximum viscosity ratio', which it
       * also is for phi >= phi_c) and mu(J) = tan(phi_c') + J + 5/2 phi_c
       * J^1/2 (tan(phi_c') for phi >= phi_c), J = (phi_c / phi - 1)^2.
       */
      std::pair<double, double>
      suspension(const double phi) const
      {
        if (!(phi < critical_fraction))
          return {maximum_ratio, critical_friction};
        const double sqrt_J = critical_fraction / phi - 1;
        const double J      = sqrt_J * sqrt_J;
        const double mu =
          critical_friction + J + 2.5 * critical_fraction * sqrt_J;
        return {mu < maximum_ratio * J ? mu / J : maximum_ratio, mu};
      }

      /// The viscous part of the stress, kept in state variables 2-7.
      static SymmetricTensor<2, 3>
      viscous_stress(const ArrayView<double> &state)
      {
        SymmetricTensor<2, 3> viscous;
        for (unsigned int c = 0; c < 6; ++c)
          viscous[SymmetricTensor<2, 3>::unrolled_to_component_indices(c)] =
            state[2 + c];
        return viscous;
      }

      /// The elastic-plastic stress of the contacts (rate-independent).
      void
      update_contact_stress(const SymmetricTensor<2, 3> &strain_increment,
                            SymmetricTensor<2, 3>       &stress,
                            const ArrayView<double>     &state) const
      {
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

    public:
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
        return fluid_viscosity > 0 ? 8 : 2;
      }

      std::vector<std::string>
      state_variable_names() const override
      {
        std::vector<std::string> names{"plastic_shear_strain",
                                       "volume_fraction"};
        if (fluid_viscosity > 0)
          for (const std::string component :
               {"xx", "yy", "zz", "xy", "xz", "yz"})
            names.push_back("viscous_stress_" + component);
        return names;
      }

      void
      initialize_state(const ArrayView<double> &state) const override
      {
        AssertIndexRange(n_state_variables() - 1, state.size());
        state[0] = 0;
        state[1] = initial_fraction;
        for (unsigned int c = 2; c < n_state_variables(); ++c)
          state[c] = 0;
      }

    private:
      IsotropicElasticity elasticity;
      double              bulk_modulus      = 0;
      double              critical_friction = 0;
      double              critical_fraction = 0.58;
      double              initial_fraction  = 0.58;
      double              dilatancy         = 4;
      double              fluid_viscosity   = 0;
      double              maximum_ratio     = 1000;
      bool                shear_induced_pressure = true;
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
