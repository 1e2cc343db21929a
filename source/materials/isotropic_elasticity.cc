#include <mpm/base/input_error.h>
#include <mpm/materials/isotropic_elasticity.h>

namespace MPM
{
  void
  IsotropicElasticity::declare_parameters(ParameterHandler &prm)
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
  IsotropicElasticity::parse_parameters(ParameterHandler  &prm,
                                        const std::string &model)
  {
    youngs_modulus = prm.get_double("Young's modulus");
    poisson_ratio  = prm.get_double("Poisson's ratio");
    check_input(youngs_modulus > 0,
                model + "/Young's modulus = " + std::to_string(youngs_modulus) +
                  " Pa: must be > 0.");
    check_input(poisson_ratio > -1 && poisson_ratio < 0.5,
                model + "/Poisson's ratio = " + std::to_string(poisson_ratio) +
                  ": must lie in (-1, 0.5); 0.5 would be incompressible.");
    shear_modulus = youngs_modulus / (2 * (1 + poisson_ratio));
    lambda        = youngs_modulus * poisson_ratio /
             ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }
} // namespace MPM
