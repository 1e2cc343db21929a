#include <mpm/base/function_input.h>
#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/materials/material_library.h>

#include <cmath>
#include <sstream>

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
    prm.declare_entry(
      "Strength reduction factor",
      "1",
      Patterns::Anything(),
      "The shear strength reduction of slope stability analysis: a "
      "function of time t (s), F(t) > 0, by which the cohesion c and "
      "tan(phi) of every material with a frictional strength ('mohr "
      "coulomb', 'drucker prager'; peak and residual strength of a "
      "softening one) are divided from the step that starts at t; the "
      "dilation angle is kept unless it exceeds the reduced friction angle. "
      "Other models are not changed. A constant F run after run gives the "
      "factor of safety as the smallest F at which the slope fails "
      "(scripts/strength_reduction.sh); a ramp such as '1 + 0.05 * t' "
      "finds it in one run if the ramp is slow against the slope's "
      "response; '1 + 0.5 * (t >= 2)' releases a slope settled over 2 s. "
      "Constants _pi and _e are known.");
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        prm.declare_entry("Density",
                          "1000",
                          Patterns::Double(),
                          "Mass density in kg/m^3; must be > 0. Of a "
                          "saturated material (Porosity > 0) the solid's "
                          "mass per volume of the mixture, the dry density "
                          "(1 - n) rho_s.");
        prm.declare_entry(
          "Minimum density",
          "0",
          Patterns::Double(),
          "Lower bound of a material point's density m_p / V_p in kg/m^3, "
          "at most 'Density'; 0: none. A point whose volume would grow "
          "beyond m_p / (minimum density) keeps that volume (and its CPDI "
          "domain shrinks with it). For a granular material, its loosest "
          "state: beyond it the grains have lost contact, and a point "
          "that leaves the flow under a tension cutoff carries no stress "
          "whatever its volume; without a bound its volume can grow "
          "without limit (2,200 times in a column collapse, "
          "doc/robustness.md) and, landing again, a point of that volume "
          "is struck by the first compression with the force of as many "
          "points.");
        prm.declare_entry(
          "Porosity",
          "0",
          Patterns::Double(0, 1),
          "Porosity n of a saturated material, 0 <= n < 1: 0 (dry) "
          "or the volume fraction of its pores, which are full of water "
          "('Pore water'; doc/pore_water.md). Then 'Density' is the "
          "solid's mass per volume of the mixture, the dry density "
          "(1 - n) rho_s, and the model's stress is the effective "
          "stress.");
        prm.declare_entry(
          "Permeability",
          "0",
          Patterns::Double(0),
          "Intrinsic permeability k in m^2 of a saturated material "
          "(Porosity > 0); must then be > 0. Its hydraulic conductivity "
          "is k rho_w g / mu (1e-11 m^2 is about 1e-4 m/s).");
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
    strength_reduction_expression = prm.get("Strength reduction factor");
    strength_reduction.reset();
    current_strength_reduction = 1;
    if (Utilities::trim(strength_reduction_expression) != "1")
      {
        strength_reduction = std::make_unique<FunctionParser<1>>(1);
        parse_function_or_throw(
          "Materials/Strength reduction factor = '" +
            strength_reduction_expression + "'",
          [&]() {
            strength_reduction->initialize("t",
                                           strength_reduction_expression,
                                           {});
            strength_reduction->value(Point<1>());
          });
      }
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        Material m;
        m.name    = name;
        m.density = prm.get_double("Density");
        check_input(m.density > 0,
                    "Materials/" + name + "/Density = " +
                      prm.get("Density") + ": must be > 0 (kg/m^3).");
        m.minimum_density = prm.get_double("Minimum density");
        check_input(m.minimum_density >= 0 &&
                      m.minimum_density <= m.density,
                    "Materials/" + name + "/Minimum density = " +
                      prm.get("Minimum density") +
                      ": must be at least 0 and at most the material's "
                      "Density, " + prm.get("Density") + " kg/m^3.");
        m.porosity     = prm.get_double("Porosity");
        m.permeability = prm.get_double("Permeability");
        check_input(m.porosity < 1,
                    "Materials/" + name + "/Porosity = " +
                      prm.get("Porosity") + ": must be below 1.");
        check_input(m.porosity == 0 || m.permeability > 0,
                    "Materials/" + name + "/Permeability = " +
                      prm.get("Permeability") +
                      ": a saturated material (Porosity " +
                      prm.get("Porosity") + ") needs a permeability > 0 "
                      "(m^2).");
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
        n_state_slots = std::max(n_state_slots, m.model->n_state_variables());
        materials.push_back(std::move(m));
        prm.leave_subsection();
      }
    prm.leave_subsection();
    if (strength_reduction)
      {
        bool frictional = false;
        for (const auto &m : materials)
          frictional = frictional || m.model->has_frictional_strength();
        check_input(frictional,
                    "Materials/Strength reduction factor = '" +
                      strength_reduction_expression +
                      "', but no material has a frictional strength "
                      "(models 'mohr coulomb', 'drucker prager'): there is "
                      "nothing to reduce.");
      }
  }


  void
  MaterialLibrary::set_time(const double time)
  {
    if (!strength_reduction)
      return;
    const double factor = strength_reduction->value(Point<1>(time));
    if (!(std::isfinite(factor) && factor > 0))
      {
        std::ostringstream message;
        message << "Materials/Strength reduction factor = '"
                << strength_reduction_expression << "' is " << factor
                << " at t = " << time << " s: it must be > 0.";
        throw InputError(message.str());
      }
    if (factor == current_strength_reduction)
      return;
    current_strength_reduction = factor;
    for (auto &m : materials)
      if (m.model->has_frictional_strength())
        m.model->set_strength_reduction(factor);
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


  double
  MaterialLibrary::max_wave_speed() const
  {
    double c = 0;
    for (const auto &m : materials)
      c = std::max(c, m.wave_speed());
    return c;
  }


  double
  MaterialLibrary::max_kinematic_viscosity() const
  {
    double nu = 0;
    for (const auto &m : materials)
      nu = std::max(nu, m.model->maximum_viscosity() / m.density);
    return nu;
  }


  bool
  MaterialLibrary::has_state_dependent_stiffness() const
  {
    for (const auto &m : materials)
      if (m.state_dependent_stiffness)
        return true;
    return false;
  }


  bool
  MaterialLibrary::has_volume_bound() const
  {
    for (const auto &m : materials)
      if (m.minimum_density > 0)
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
