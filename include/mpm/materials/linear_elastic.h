#ifndef mpm_materials_linear_elastic_h
#define mpm_materials_linear_elastic_h

#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * Isotropic linear elasticity in rate form, sigma += lambda tr(de) I
     * + 2 mu de (plane strain in 2D). No state variables.
     */
    class LinearElastic : public MaterialModel
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double>     &state,
                    const double                 time_step) const override;

      double
      strain_energy_density(const SymmetricTensor<2, 3> &stress) const override;

      double
      p_wave_modulus() const override;

      double
      default_k0() const override;

    private:
      IsotropicElasticity elasticity;
    };
  } // namespace MaterialModels
} // namespace MPM

#endif
