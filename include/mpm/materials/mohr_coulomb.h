#ifndef mpm_materials_mohr_coulomb_h
#define mpm_materials_mohr_coulomb_h

#include <mpm/materials/frictional_strength.h>
#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

#include <array>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * Linear elastic - perfectly plastic Mohr-Coulomb model with a tension
     * cutoff (a Rankine limit on the largest principal stress) and
     * non-associated flow through a dilation angle, for dry granular flow.
     * Plane strain in 2D (the zz stress evolves like the others).
     *
     * With principal stresses sorted s1 >= s2 >= s3 (tension positive) the
     * admissible set is
     *   f  = (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) <= 0,
     *   s1 <= T,
     * and the plastic potential of the shear planes is f with psi in place
     * of phi, so that psi = 0 gives no plastic volume change. The tension
     * cutoff flows associatively (it opens the material).
     *
     * The stress update is an elastic predictor followed by a return in
     * principal stress space (de Souza Neto, Peric and Owen, Computational
     * Methods for Plasticity, 2008, section 8.2). All surfaces are planes
     * in principal stress space and there is no hardening, so for a given
     * set of active surfaces the return is the solution of a linear system
     * of at most 3 equations, without iterations: it is exact and stable
     * however far outside the trial stress lies. The active set (main
     * plane, one of the two edges, the tension plane, the corners and the
     * apex) is found by trying the candidate sets from the fewest surfaces
     * up and accepting the first whose multipliers are non-negative and
     * whose stress is admissible and keeps the principal ordering; see
     * return_principal() and doc/materials.md.
     *
     * State: the accumulated equivalent plastic shear strain
     * kappa = sum sqrt(2/3 de_p : de_p) (de_p the deviatoric plastic strain
     * increment), which shows where the material has yielded.
     *
     * Strain softening (subsection 'Strain softening', off by default):
     * phi, psi and c go linearly from their peak values to residual ones
     * as kappa goes from 'Peak plastic shear strain' to 'Residual plastic
     * shear strain' (the form of CB-Geo MPM and Anura3D), and the tension
     * cutoff is min(T, c cot(phi)). The return is implicit in kappa: the
     * strength is the one at the step's final kappa, found by regula falsi
     * on kappa_n + dkappa(kappa) = kappa, bracketed by the peak-side
     * (kappa_n) and residual strengths, so that a returned stress lies on
     * the surface of its own kappa (return_with_softening()). Points
     * before the peak or past the residual strain use surfaces prepared
     * once, like a model without softening; only points inside the
     * softening range pay for surfaces built on the fly.
     *
     * Softening localises in bands as narrow as the mesh allows, so the
     * strain-softening law needs a length. Two are offered. 'Reference cell
     * size' scales the softening strains by the cell size (a band one cell
     * wide dissipates the same on every mesh). 'Nonlocal radius' R gives
     * the strength a non-local argument: the step writes into state
     * variable 1 the over-nonlocal kappa* = (1 - m) kappa + m kappa_avg
     * (kappa_avg the average over the points within R, m the 'Over-nonlocal
     * factor'; NonlocalAveraging) from the kappa of the step before, and
     * the return is then made at the fixed strength of kappa* (explicit in
     * the regularised strain, no iteration) while the point's own kappa
     * accumulates the plastic increment. The band width is then set by R,
     * not by the cells (Vermeer and Brinkgreve 1994, Galavi and Schweiger
     * 2010; m > 1 because with m = 1 the plastic zone of a softening
     * plasticity model can still shrink to one cell, Jirasek and Rolshoven
     * 2003).
     */
    class MohrCoulomb : public FrictionalModel
    {
    public:
      /**
       * The yield surfaces of the return in the sorted principal frame, as
       * bits of the value return_principal() gives back. shear_13 is the
       * main Mohr-Coulomb plane; shear_12 joins it along the triaxial
       * extension edge (s2 = s3), shear_23 along the triaxial compression
       * edge (s1 = s2). tension_i is s_i <= T.
       */
      enum Surface : unsigned int
      {
        shear_13  = 1,
        shear_12  = 2,
        shear_23  = 4,
        tension_1 = 8,
        tension_2 = 16,
        tension_3 = 32,
        /**
         * No candidate set was acceptable and the stress was put on the
         * apex of the admissible set. Never observed; reported so that
         * the unit test can count it.
         */
        fallback = 64
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
       * With softening regularised ('Strain softening/Reference cell
       * size' > 0), the softening strains scaled by @p cell_size / the
       * reference size; else update_stress().
       */
      void
      update_stress_in_cell(const SymmetricTensor<2, 3> &strain_increment,
                            SymmetricTensor<2, 3>       &stress,
                            const ArrayView<double>     &state,
                            const double                 time_step,
                            const double cell_size) const override;

      double
      strain_energy_density(const SymmetricTensor<2, 3> &stress) const override;

      double
      p_wave_modulus() const override;

      /**
       * With 'Strain softening/Nonlocal radius' > 0, the plastic shear
       * strain (state variable 0) regularised into state variable 1, which
       * sets the strength (see the class documentation); else null.
       */
      const NonlocalVariable *
      nonlocal_variable() const override
      {
        return nonlocal_state ? &nonlocal : nullptr;
      }

      /**
       * Divide peak and residual strength (FrictionalStrength::reduced())
       * and prepare their surfaces again.
       */
      void
      set_strength_reduction(const double factor) override;

      /**
       * The return mapping in principal stress space: on input the trial
       * principal stresses sorted s[0] >= s[1] >= s[2], on output the
       * returned ones (still sorted). Returns 0 for an elastic step, else
       * the Surface bits of the active set. Public so that the unit test
       * can see which case was taken.
       */
      unsigned int
      return_principal(std::array<double, 3> &s) const;

    private:
      struct CandidateSet;
      struct YieldSurfaces;

      /**
       * The body of return_principal(), inlined into update_stress() so
       * that the principal values stay in registers: passed through
       * memory, they were written one by one and read back in pairs, and
       * the store-forwarding stalls cost more than the arithmetic.
       *
       * @p plastic_shear_increment is the increment of the accumulated
       * plastic shear strain (0 for an elastic step): for a return to one
       * plane |dgamma| times the plane's shear_strain_per_multiplier,
       * otherwise from the stress change.
       *
       * @p prepared: whether @p surfaces has its candidate sets prepared
       * (else each is prepared when tried); a template argument, so that
       * the prepared path has no branch for it.
       */
      template <bool prepared>
      inline unsigned int
      return_principal_inline(const YieldSurfaces   &surfaces,
                              std::array<double, 3> &s,
                              double &plastic_shear_increment) const;

      /**
       * update_stress() for a material with or without softening (the
       * two paths compiled apart).
       */
      template <bool with_softening>
      inline void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double>     &state,
                    const double                 kappa_scale) const;

      /// update_stress<true>, a function of its own: called from
      /// update_stress(), it leaves the path without softening as
      /// compact as a model without softening.
      void
      update_stress_with_softening(
        const SymmetricTensor<2, 3> &strain_increment,
        SymmetricTensor<2, 3>       &stress,
        const ArrayView<double>     &state,
        const double                 kappa_scale) const;

      /**
       * The return of a softening material at @p kappa (see the class
       * documentation): implicit in kappa. The softening range is divided
       * by @p kappa_scale (the cell size over the reference size; 1 when
       * not regularised). With @p fixed_strength (the non-local
       * regularisation, @p kappa the regularised strain) the return is made
       * at the strength of @p kappa alone, without the search.
       */
      unsigned int
      return_with_softening(std::array<double, 3> &s,
                            double                &plastic_shear_increment,
                            const double           kappa,
                            const double           kappa_scale,
                            const bool             fixed_strength) const;

      /**
       * The return from the trial stress @p s at the fixed strength of
       * plastic shear strain @p kappa within the softening range
       * [@p start, @p end] (the prepared surfaces at the peak and residual
       * strengths, else surfaces built for this return).
       */
      unsigned int
      return_at_kappa(std::array<double, 3> &s,
                      double                &plastic_shear_increment,
                      const double           kappa,
                      const double           start,
                      const double           end) const;

      /**
       * Try one candidate set of @p m active planes (a template argument,
       * so that the loops over the set unroll; the sets are tried in the
       * order of candidate_topology()). On success, @p x holds the
       * returned principal stresses and the function returns true.
       */
      template <unsigned int m>
      inline bool
      try_candidate_set(const YieldSurfaces         &surfaces,
                        const CandidateSet          &set,
                        const std::array<double, 3> &trial,
                        const std::array<double, 6> &f_trial,
                        const double                 tol,
                        const double                 multiplier_tol,
                        std::array<double, 3>       &x,
                        double &first_multiplier) const;

      /// The strength parameters (angles in radians, stresses in Pa).
      using Strength = FrictionalStrength;

      /**
       * Whether the sorted principal stresses @p s lie inside the
       * admissible set of @p strength: the elastic check of
       * return_principal_inline() with the surfaces of @p strength, to the
       * last bit, without building them.
       */
      bool
      is_elastic(const Strength &strength, const std::array<double, 3> &s) const;

      /// The strength at accumulated plastic shear strain @p kappa, with
      /// the softening range [@p start, @p end] of the point.
      Strength
      strength_at(const double kappa,
                  const double start,
                  const double end) const;

      /**
       * The surfaces of @p strength, with every candidate set prepared if
       * @p prepare_sets (surfaces used for many returns) or none (the
       * surfaces of one softening point's return: each set is prepared
       * when it is tried).
       */
      YieldSurfaces
      make_surfaces(const Strength &strength, const bool prepare_sets) const;

      /**
       * Fill what of @p set depends on the material (its inverse, whether
       * it is independent, its corner), from @p surfaces' planes.
       */
      static void
      prepare_candidate_set(const YieldSurfaces &surfaces, CandidateSet &set);

      /**
       * The candidate sets (which planes are active) in the order they are
       * tried, the same for every material.
       */
      static const std::vector<CandidateSet> &
      candidate_topology();

      IsotropicElasticity elasticity;
      /// Without softening the strength; with it the peak strength (both
      /// divided by the strength reduction factor).
      Strength peak_strength;
      /// The residual strength (softening only), reduced like the peak.
      Strength residual_strength;
      /// The residual strength as given in the parameter file (the peak
      /// one is FrictionalModel::given_strength).
      Strength given_residual_strength;
      bool     softening = false;
      /// The range of kappa over which the strength softens.
      double softening_start = 0;
      double softening_end   = 0;
      /// 'Reference cell size' (0: not regularised).
      double reference_cell_size = 0;
      /// The non-local regularisation ('Nonlocal radius' > 0; then
      /// nonlocal_state is set).
      NonlocalVariable nonlocal;

      /**
       * A candidate active set with what depends only on the material:
       * the inverse of its matrix A_ij = a_i . r_j (the multipliers are
       * A^-1 f_trial) and, for three planes, the point where they meet.
       * Computed once, so that a return costs a few products per set
       * instead of an elimination (it was a third of the flume's run time).
       */
      struct CandidateSet
      {
        unsigned int                         bits = 0;
        unsigned int                         m    = 0;
        std::array<unsigned int, 3>          active{};
        bool                                 independent = false;
        std::array<std::array<double, 3>, 3> inverse{};
        bool                                 corner_defined = false;
        std::array<double, 3>                corner{};
      };

      /**
       * The admissible set of one strength: the six surfaces
       * f_k = a_k . s - b_k in the sorted principal frame, their elastic
       * return directions r_k = D n_k (n_k the flow direction) and the
       * prepared candidate sets.
       */
      struct YieldSurfaces
      {
        std::array<std::array<double, 3>, 6> gradient;
        std::array<std::array<double, 3>, 6> return_direction;
        std::array<double, 6>                bound;
        double                               tension_cutoff = 0;
        /**
         * For a return to plane k alone, the plastic shear strain per unit
         * multiplier: the stress change is dgamma r_k, so the increment
         * sqrt(2/3 |dev(s_trial - s)|^2) / (2 G) is |dgamma| times this
         * constant. Saves the square root at the end of most returns
         * (with it, the accumulation of a state that nothing else reads
         * was a fifth of the model's time in the flume).
         */
        std::array<double, 6> shear_strain_per_multiplier{};
        /// In the order of candidate_topology(); empty if not prepared.
        std::vector<CandidateSet> candidate_sets;

        /**
         * The value of plane @p k at principal stresses @p x:
         * f_k(x) = a_k . x - bound_k (positive outside).
         */
        double
        plane_value(const unsigned int k, const std::array<double, 3> &x) const
        {
          return gradient[k][0] * x[0] + gradient[k][1] * x[1] +
                 gradient[k][2] * x[2] - bound[k];
        }
      };

      /// The prepared surfaces: of the strength without softening, else of
      /// the peak strength.
      YieldSurfaces peak;
      /// The prepared surfaces of the residual strength (softening only).
      YieldSurfaces residual;
      /// 1 / (2 G), for the deviatoric plastic strain.
      double inverse_two_shear_modulus = 0;
    };
  } // namespace MaterialModels
} // namespace MPM

#endif
