#include <mpm/base/plugin_registry.h>
#include <mpm/materials/objective_stress_rate.h>

namespace MPM
{
  void
  ObjectiveStressRate::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Objective stress rate",
      "jaumann",
      Patterns::Selection("jaumann|none"),
      "How a point's stress follows its rotation before its model adds the "
      "step's increment. 'jaumann': the Jaumann rate, integrated by the "
      "exactly orthogonal rotation of Hughes and Winget (1980); a stressed "
      "body that rotates carries its stress with it. 'none': the stress "
      "components are integrated in the fixed axes (not objective: a "
      "rotating stressed body keeps its stress fixed in space). "
      "doc/materials.md has the simple-shear check of both and what the "
      "choice changes in the shipped scenes.");
  }


  void
  ObjectiveStressRate::parse_parameters(ParameterHandler &prm)
  {
    rate = select_choice<Type>(prm.get("Objective stress rate"),
                               {{"jaumann", Type::jaumann},
                                {"none", Type::none}},
                               "Materials/Objective stress rate");
  }
} // namespace MPM
