#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/materials/material_library.h>

#include <cmath>

namespace MPM
{
  double
  Material::wave_speed() const
  {
    return std::sqrt(model->p_wave_modulus() / density);
  }


  void
  MaterialLibrary::declare_name_list(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    prm.declare_entry("List of materials",
                      "material",
                      Patterns::Anything(),
                      "Comma separated names of the materials of the scene; "
                      "each name has a subsection of its own in 'Materials'.");
    prm.leave_subsection();
  }


  std::vector<std::string>
  MaterialLibrary::read_name_list(ParameterHandler &prm)
  {
    prm.enter_subsection("Materials");
    const auto names = split_name_list(prm.get("List of materials"),
                                       "Materials/List of materials");
    prm.leave_subsection();
    check_input(!names.empty(),
                "'Materials/List of materials' is empty: give at least one "
                "material.");
    return names;
  }


  void
  MaterialLibrary::declare_parameters(ParameterHandler               &prm,
                                      const std::vector<std::string> &names)
  {
    declare_name_list(prm);
    prm.enter_subsection("Materials");
    ObjectiveStressRate::declare_parameters(prm);
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        prm.declare_entry("Density",
                          "1000",
                          Patterns::Double(),
                          "Mass density in kg/m^3; must be > 0.");
        prm.declare_entry("Model",
                          "linear elastic",
                          Patterns::Selection(
                            MaterialModelFactory::model_names()),
                          "Constitutive model; its parameters are in the "
                          "subsection of the same name.");
        MaterialModelFactory::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  void
  MaterialLibrary::parse_parameters(ParameterHandler &prm)
  {
    const auto names = read_name_list(prm);
    prm.enter_subsection("Materials");
    stress_rate.parse_parameters(prm);
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        Material m;
        m.name    = name;
        m.density = prm.get_double("Density");
        check_input(m.density > 0,
                    "Materials/" + name + "/Density = " +
                      prm.get("Density") + ": must be > 0 (kg/m^3).");
        const std::string model = prm.get("Model");
        try
          {
            m.model = MaterialModelFactory::create(model, prm);
          }
        catch (const InputError &e)
          {
            // The models name their parameters relative to their own
            // subsection ("mohr coulomb/Friction angle"); with several
            // materials the user needs the whole path.
            const std::string message = e.what();
            throw InputError("Materials/" + name +
                             (message.rfind(model + "/", 0) == 0 ? "/" : ": ") +
                             message);
          }
        m.state_dependent_stiffness = m.model->stiffness_depends_on_state();
        materials.push_back(std::move(m));
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  unsigned int
  MaterialLibrary::index_of(const std::string &name,
                            const std::string &parameter) const
  {
    for (unsigned int i = 0; i < materials.size(); ++i)
      if (materials[i].name == name)
        return i;
    std::string known;
    for (const auto &m : materials)
      known += (known.empty() ? "" : ", ") + m.name;
    throw InputError(parameter + " = '" + name +
                     "' is not a material of 'Materials/List of materials' (" +
                     known + ").");
  }


  unsigned int
  MaterialLibrary::max_n_state_variables() const
  {
    unsigned int n = 0;
    for (const auto &m : materials)
      n = std::max(n, m.model->n_state_variables());
    return n;
  }


  double
  MaterialLibrary::max_wave_speed() const
  {
    double c = 0;
    for (const auto &m : materials)
      c = std::max(c, m.wave_speed());
    return c;
  }


  bool
  MaterialLibrary::has_state_dependent_stiffness() const
  {
    for (const auto &m : materials)
      if (m.state_dependent_stiffness)
        return true;
    return false;
  }


  double
  MaterialLibrary::max_constant_wave_speed() const
  {
    double c = 0;
    for (const auto &m : materials)
      if (!m.state_dependent_stiffness)
        c = std::max(c, m.wave_speed());
    return c;
  }
} // namespace MPM
