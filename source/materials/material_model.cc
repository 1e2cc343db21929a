#include <mpm/base/input_error.h>
#include <mpm/materials/material_model.h>

namespace MPM
{
  namespace MaterialModelFactory
  {
    namespace
    {
      struct Entry
      {
        std::string description;
        Declarer    declare;
        Creator     create;
      };

      // A function-local static, so that registration from other
      // translation units' static initialisers never runs before the map is
      // constructed.
      std::map<std::string, Entry> &
      registry()
      {
        static std::map<std::string, Entry> models;
        return models;
      }
    } // namespace


    bool
    register_model(const std::string &name,
                   const std::string &description,
                   const Declarer    &declare,
                   const Creator     &create)
    {
      registry()[name] = Entry{description, declare, create};
      return true;
    }


    std::string
    model_names()
    {
      std::string names;
      for (const auto &[name, entry] : registry())
        names += (names.empty() ? "" : "|") + name;
      return names;
    }


    void
    declare_parameters(ParameterHandler &prm)
    {
      for (const auto &[name, entry] : registry())
        {
          prm.enter_subsection(name);
          entry.declare(prm);
          prm.leave_subsection();
        }
    }


    std::unique_ptr<MaterialModel>
    create(const std::string &name, ParameterHandler &prm)
    {
      const auto it = registry().find(name);
      check_input(it != registry().end(),
                  "Unknown material model '" + name + "'; known models: " +
                    model_names() + ".");
      auto model = it->second.create();
      prm.enter_subsection(name);
      model->parse_parameters(prm);
      prm.leave_subsection();
      return model;
    }
  } // namespace MaterialModelFactory
} // namespace MPM
