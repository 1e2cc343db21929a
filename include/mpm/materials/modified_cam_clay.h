#ifndef mpm_materials_modified_cam_clay_h
#define mpm_materials_modified_cam_clay_h

#include <mpm/materials/material_model.h>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * Modified Cam-Clay (Roscoe and Burland 1968), the critical-state model
     * of a saturated clay in effective stress, with hypoelastic
     * pressure-dependent stiffness. Plane strain in 2D.
     *
     * With p = -tr(sigma) / 3 (compression positive) and q = sqrt(3 J2),
     * the yield surface is the ellipse
     *   f = q^2 / M^2 + p (p - p_c) <= 0
     * through the origin and (p_c, 0), whose top lies on the critical
     * state line q = M p. The flow is associated. The preconsolidation
     * pressure p_c hardens with the plastic volumetric strain (compression
     * positive) as dp_c / p_c = v / (lambda - kappa) d eps_v^p, and the
     * elastic bulk modulus is K = v p / kappa, so that isotropic loading
     * follows the normal compression line (slope lambda in v - ln p) and
     * unloading a swelling line (slope kappa). The shear modulus is either
     * G = 3 (1 - 2 nu) / (2 (1 + nu)) K (constant Poisson's ratio) or a
     * constant. Like every hypoelastic Cam-Clay, neither choice derives
     * from a strain energy (Zytynski et al. 1978): a closed elastic cycle
     * can produce or dissipate a little energy.
     *
     * The stress update (update_stress(), details in
     * doc/materials.md, "Modified Cam-Clay"):
     * - the elastic predictor integrates K = v p / kappa exactly over the
     *   step (v fixed at its start): p = p_n exp(v d eps_v / kappa),
     *   compression positive, and s = s_n + 2 G de with G at the start of
     *   the step;
     * - outside the surface, an implicit (backward Euler) return in (p, q)
     *   with the hardening (Borja and Lee 1990; de Souza Neto, Peric and
     *   Owen 2008, chapter 10): Newton on the plastic multiplier and the
     *   plastic volumetric strain, the elastic law and the hardening both
     *   integrated exactly in the latter. Converged when the yield function
     *   is below 1e-11 p_c^2 and the flow rule's residual below 1e-11
     *   kappa / v; an increment whose elastic pressure ratio or shear
     *   exceeds a bound is cut into sub-steps, and a step whose Newton does
     *   not converge in 50 iterations is retried with more sub-steps; past
     *   4096 sub-steps the update throws, naming the point's state.
     *
     * No tension: below the 'Minimum pressure' p_min the bulk modulus is
     * held at v p_min / kappa (so that a point with zero stress is not
     * without stiffness), and an increment whose elastic trial pressure is
     * not positive puts the stress at the apex of the surface, sigma = 0
     * (the clay has lost contact), the whole rest of the increment being
     * plastic; p_c is then left as it is.
     *
     * A point whose stress at the start of an update lies outside the
     * surface (for instance a geostatic stress deeper than the uniform
     * 'Initial preconsolidation pressure' allows) is taken as normally
     * consolidated at that stress: p_c is raised to put it on the surface.
     *
     * State: the preconsolidation pressure p_c, the specific volume
     * v = 1 + e (following the kinematics, dv / v = d eps_v), the
     * accumulated equivalent plastic shear strain sqrt(2/3 e_p : e_p) (as
     * in Mohr-Coulomb) and the plastic volumetric strain (tension positive,
     * as every strain in the code: negative when the clay compacts).
     */
    class ModifiedCamClay : public MaterialModel
    {
    public:
      /// Indices of the state variables.
      enum StateVariable : unsigned int
      {
        preconsolidation_pressure = 0,
        specific_volume           = 1,
        plastic_shear_strain      = 2,
        plastic_volumetric_strain = 3
      };

      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double>     &state,
                    const double                 time_step) const override;

      /**
       * The energy of the tangent (linearised) elasticity at the given
       * stress, 1/2 (p^2 / K + q^2 / (3 G)), with K and G at that stress
       * and the initial specific volume: the hypoelastic law has no strain
       * energy of its own, and the energy statistics need a number.
       */
      double
      strain_energy_density(const SymmetricTensor<2, 3> &stress) const override;

      /**
       * K + 4/3 G at the initial preconsolidation pressure and specific
       * volume: an estimate for what asks without a point's state. The
       * time step uses the state-dependent one.
       */
      double
      p_wave_modulus() const override;

      bool
      stiffness_depends_on_state() const override
      {
        return true;
      }

      using MaterialModel::p_wave_modulus;

      /**
       * The elastic nu / (1 - nu) of uniaxial strain; for a normally
       * consolidated clay Jaky's 1 - sin(phi) would be closer, but M does
       * not fix phi without choosing compression or extension.
       */
      double
      default_k0() const override;

      unsigned int
      n_state_variables() const override;

      std::vector<std::string>
      state_variable_names() const override;

      void
      initialize_state(const ArrayView<double> &state) const override;

      /// The bulk modulus v max(p, p_min) / kappa.
      double
      bulk_modulus(const double p, const double v) const;

      /// The shear modulus that goes with the bulk modulus @p K.
      double
      shear_modulus(const double K) const;

    protected:
      /**
       * K + 4/3 G at the point's pressure (at least p_min) and specific
       * volume.
       */
      double
      p_wave_modulus_at_state(
        const SymmetricTensor<2, 3>   &stress,
        const ArrayView<const double> &state) const override;

    private:
      /**
       * One update with a sub-step count @p n_sub: false if a Newton
       * iteration did not converge (stress and state are then unchanged).
       */
      bool
      update_in_substeps(const SymmetricTensor<2, 3> &strain_increment,
                         SymmetricTensor<2, 3>       &stress,
                         const ArrayView<double>     &state,
                         const unsigned int           n_sub) const;

      /**
       * One backward Euler step; false if its Newton iteration did not
       * converge.
       */
      bool
      update_one_step(const SymmetricTensor<2, 3> &strain_increment,
                      SymmetricTensor<2, 3>       &stress,
                      double                      *state) const;

      /**
       * The pressure after an elastic volumetric strain @p d (compression
       * positive) from @p p_n, at specific volume @p v: the exact
       * integral of dp = v max(p, p_min) / kappa dd (exponential above
       * p_min, linear below).
       */
      double
      elastic_pressure(const double p_n, const double d, const double v) const;

      double M                  = 1;
      double lambda             = 0.2;
      double kappa              = 0.05;
      double initial_void_ratio = 1;
      double initial_preconsolidation_pressure = 100e3;
      double poisson_ratio                     = 0.3;
      bool   constant_shear_modulus            = false;
      double constant_G                        = 0;
      double minimum_pressure                  = 1e3;
    };
  } // namespace MaterialModels
} // namespace MPM

#endif
