#include <mpm/base/input_error.h>
#include <mpm/materials/linear_elastic.h>

namespace MPM
{
  namespace MaterialModels
  {
    void
    LinearElastic::declare_parameters(ParameterHandler &prm)
    {
      IsotropicElasticity::declare_parameters(prm);
    }


    void
    LinearElastic::parse_parameters(ParameterHandler &prm)
    {
      elasticity.parse_parameters(prm, "linear elastic");
    }


    void
    LinearElastic::update_stress(const SymmetricTensor<2, 3> &strain_increment,
                                 SymmetricTensor<2, 3>       &stress,
                                 const ArrayView<double> &,
                                 const double) const
    {
      elasticity.add_stress_increment(strain_increment, stress);
    }


    double
    LinearElastic::strain_energy_density(
      const SymmetricTensor<2, 3> &stress) const
    {
      return elasticity.strain_energy_density(stress);
    }


    double
    LinearElastic::p_wave_modulus() const
    {
      return elasticity.p_wave_modulus();
    }


    double
    LinearElastic::default_k0() const
    {
      return elasticity.poisson_ratio / (1 - elasticity.poisson_ratio);
    }
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(MPM::MaterialModels::LinearElastic,
                            "linear elastic",
                            "Isotropic linear elasticity (plane strain in 2D).")
