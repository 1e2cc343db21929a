#ifndef mpm_base_plugin_registry_h
#define mpm_base_plugin_registry_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/base/input_error.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace MPM
{
  using namespace dealii;

  /**
   * The registry of one kind of plugin (a weight function, a basal law, a
   * postprocessor): each implementation registers, from its own file, its
   * name, a one-line description, a function that declares its parameters
   * and a function that creates it (MPM_REGISTER_PLUGIN). The parameter
   * file names the implementation; an unknown name is an InputError that
   * lists the choices.
   *
   * @tparam Interface the plugin's base class.
   * @tparam Args what the creator receives besides the ParameterHandler
   * (e.g. the context the plugin works on).
   *
   * Creation: create() enters the subsection named like the plugin (where
   * the plugin declared its parameters) if the plugin declared any, and
   * hands the ParameterHandler to the creator, which parses them.
   */
  template <class Interface, typename... Args>
  class PluginRegistry
  {
  public:
    using Declarer = std::function<void(ParameterHandler &)>;
    using Creator =
      std::function<std::unique_ptr<Interface>(ParameterHandler &, Args...)>;

    struct Entry
    {
      std::string description;
      Declarer    declare;
      Creator     create;
    };

    /// Called by MPM_REGISTER_PLUGIN at program start.
    static bool
    add(const std::string &name,
        const std::string &description,
        const Declarer    &declare,
        const Creator     &create)
    {
      entries()[name] = Entry{description, declare, create};
      return true;
    }

    /// The registered names joined by '|', for a Patterns::Selection.
    static std::string
    names()
    {
      std::string joined;
      for (const auto &[name, entry] : entries())
        joined += (joined.empty() ? "" : "|") + name;
      return joined;
    }

    /// 'name: description' of every implementation, one per line, for the
    /// documentation of the parameter that chooses one.
    static std::string
    descriptions()
    {
      std::string text;
      for (const auto &[name, entry] : entries())
        text += "'" + name + "': " + entry.description + " ";
      return text;
    }

    static bool
    has(const std::string &name)
    {
      return entries().count(name) > 0;
    }

    /**
     * Declare, for every registered implementation, its subsection (named
     * like it) with its parameters, in the current subsection of @p prm.
     */
    static void
    declare_parameters(ParameterHandler &prm)
    {
      for (const auto &[name, entry] : entries())
        if (entry.declare)
          {
            prm.enter_subsection(name);
            entry.declare(prm);
            prm.leave_subsection();
          }
    }

    /**
     * Create the implementation @p name (chosen by the parameter
     * @p parameter, named in the error message), which reads its
     * parameters from its subsection of the current subsection of @p prm.
     */
    static std::unique_ptr<Interface>
    create(const std::string &name,
           const std::string &parameter,
           ParameterHandler  &prm,
           Args... args)
    {
      const auto it = entries().find(name);
      check_input(it != entries().end(),
                  parameter + " = '" + name + "' is not known; the choices: " +
                    names() + ".");
      if (!it->second.declare)
        return it->second.create(prm, std::forward<Args>(args)...);
      prm.enter_subsection(name);
      auto plugin = it->second.create(prm, std::forward<Args>(args)...);
      prm.leave_subsection();
      return plugin;
    }

  private:
    // A function-local static: registration from other translation units'
    // static initialisers never runs before the map is constructed.
    static std::map<std::string, Entry> &
    entries()
    {
      static std::map<std::string, Entry> registered;
      return registered;
    }
  };


  /**
   * Look up @p name in the table @p choices of a Patterns::Selection
   * parameter @p parameter: the value, or an InputError listing the
   * choices (never a silent fallback to one of them).
   */
  template <typename T>
  T
  select_choice(const std::string                       &name,
                const std::map<std::string, T>          &choices,
                const std::string                       &parameter)
  {
    const auto it = choices.find(name);
    if (it == choices.end())
      {
        std::string known;
        for (const auto &[n, v] : choices)
          known += (known.empty() ? "" : "|") + n;
        throw InputError(parameter + " = '" + name +
                         "' is not known; the choices: " + known + ".");
      }
    return it->second;
  }
} // namespace MPM

#define MPM_PLUGIN_CONCAT_IMPL(a, b) a##b
#define MPM_PLUGIN_CONCAT(a, b) MPM_PLUGIN_CONCAT_IMPL(a, b)

/**
 * Register a plugin with the registry @p Registry (a PluginRegistry
 * specialisation) under @p name, at the end of the plugin's own file.
 * @p declare is a function void(ParameterHandler &) declaring its
 * parameters (nullptr if it has none), @p create a callable returning a
 * std::unique_ptr to the interface from (ParameterHandler &, Args...).
 */
#define MPM_REGISTER_PLUGIN(Registry, name, description, declare, create) \
  namespace                                                                 \
  {                                                                         \
    const bool MPM_PLUGIN_CONCAT(mpm_plugin_registered_, __COUNTER__) =        \
      Registry::add(name, description, declare, create);                    \
  }

#endif
