#ifndef mpm_materials_material_library_h
#define mpm_materials_material_library_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/material_model.h>

#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * One material of a scene: a name, a density and a constitutive model.
   */
  struct Material
  {
    std::string                    name;
    double                         density = 0;
    std::unique_ptr<MaterialModel> model;

    /**
     * Elastic P-wave speed sqrt((lambda + 2 mu) / rho), for the CFL limit.
     */
    double
    wave_speed() const;
  };


  /**
   * The materials of a scene, declared in the parameter file as
   *
   *   subsection Materials
   *     set List of materials = sand, block
   *     subsection sand
   *       set Density = 1600
   *       set Model   = linear elastic
   *       subsection linear elastic
   *         ...
   *
   * A material point stores the index of its material in this list.
   */
  class MaterialLibrary
  {
  public:
    /**
     * First parsing pass: only the list of names.
     */
    static void
    declare_name_list(ParameterHandler &prm);

    static std::vector<std::string>
    read_name_list(ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler               &prm,
                       const std::vector<std::string> &names);

    void
    parse_parameters(ParameterHandler &prm);

    unsigned int
    size() const
    {
      return materials.size();
    }

    const Material &
    operator[](const unsigned int i) const
    {
      return materials[i];
    }

    /**
     * Index of the material called @p name; InputError naming
     * @p parameter if there is none.
     */
    unsigned int
    index_of(const std::string &name, const std::string &parameter) const;

    /**
     * The largest number of state variables over all models: the width of
     * the state slot of every point.
     */
    unsigned int
    max_n_state_variables() const;

    /**
     * Largest elastic wave speed of all materials.
     */
    double
    max_wave_speed() const;

  private:
    std::vector<Material> materials;
  };
} // namespace MPM

#endif
