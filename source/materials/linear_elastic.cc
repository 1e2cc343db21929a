#include <mpm/base/input_error.h>
#include <mpm/materials/linear_elastic.h>

namespace MPM
{
  namespace MaterialModels
  {
    void
    LinearElastic::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Young's modulus",
                        "1e6",
                        Patterns::Double(0),
                        "Young's modulus E in Pa; must be > 0.");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::Double(-1, 0.5),
                        "Poisson's ratio nu, in (-1, 0.5).");
    }


    void
    LinearElastic::parse_parameters(ParameterHandler &prm)
    {
      youngs_modulus = prm.get_double("Young's modulus");
      poisson_ratio  = prm.get_double("Poisson's ratio");
      check_input(youngs_modulus > 0,
                  "Linear elastic/Young's modulus = " +
                    std::to_string(youngs_modulus) + " Pa: must be > 0.");
      check_input(poisson_ratio > -1 && poisson_ratio < 0.5,
                  "Linear elastic/Poisson's ratio = " +
                    std::to_string(poisson_ratio) +
                    ": must lie in (-1, 0.5); 0.5 would be incompressible.");
      shear_modulus = youngs_modulus / (2 * (1 + poisson_ratio));
      lambda        = youngs_modulus * poisson_ratio /
               ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
    }


    void
    LinearElastic::update_stress(const SymmetricTensor<2, 3> &strain_increment,
                                 SymmetricTensor<2, 3>       &stress,
                                 const ArrayView<double> &) const
    {
      stress += lambda * trace(strain_increment) * unit_symmetric_tensor<3>() +
                2 * shear_modulus * strain_increment;
    }


    double
    LinearElastic::strain_energy_density(
      const SymmetricTensor<2, 3> &stress) const
    {
      // 1/2 sigma : C^{-1} : sigma with
      // C^{-1} sigma = (1+nu)/E sigma - nu/E tr(sigma) I.
      const double tr = trace(stress);
      return 0.5 * ((1 + poisson_ratio) / youngs_modulus * (stress * stress) -
                    poisson_ratio / youngs_modulus * tr * tr);
    }


    double
    LinearElastic::p_wave_modulus() const
    {
      return lambda + 2 * shear_modulus;
    }


    double
    LinearElastic::default_k0() const
    {
      return poisson_ratio / (1 - poisson_ratio);
    }
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(MPM::MaterialModels::LinearElastic,
                            "linear elastic",
                            "Isotropic linear elasticity (plane strain in 2D).")
