#ifndef mpm_materials_material_library_h
#define mpm_materials_material_library_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/material_model.h>
#include <mpm/materials/objective_stress_rate.h>

#include <cmath>
#include <cstring>
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
    /// 'Minimum density': a point of this material keeps a volume of at
    /// most its mass over this (0: no bound; PointUpdate::update_stress()).
    double                         minimum_density = 0;
    std::unique_ptr<MaterialModel> model;
    /// 'Porosity' n: 0 for a dry material; above 0 its pores are full of
    /// water (PoreWater) and 'Density' is the solid's mass per volume of
    /// the mixture, the dry density (1 - n) rho_s.
    double porosity = 0;
    /// 'Permeability': the intrinsic permeability k (m^2) of a saturated
    /// material; the drag on the water is n^2 mu / k (v_w - v_s).
    double permeability = 0;
    /// model->stiffness_depends_on_state(), asked once when parsed: the
    /// stress update reads it for every point.
    bool state_dependent_stiffness = false;

    /**
     * Elastic P-wave speed sqrt((lambda + 2 mu) / rho), for the CFL limit.
     */
    double
    wave_speed() const;

    /**
     * The P-wave speed at a point's @p stress and @p state, for a model
     * whose stiffness depends on them.
     */
    double
    wave_speed(const SymmetricTensor<2, 3>   &stress,
               const ArrayView<const double> &state) const
    {
      return std::sqrt(model->p_wave_modulus(stress, state) / density);
    }
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
    max_n_state_variables() const
    {
      // Kept from parse_parameters(): asked for by every point's stress
      // update (a loop of virtual calls there was 3 % of the flume's step).
      return n_state_slots;
    }

    /**
     * Largest elastic wave speed of all materials (for a material whose
     * stiffness depends on the state, the model's estimate
     * p_wave_modulus()).
     */
    double
    max_wave_speed() const;

    /**
     * Whether a material's stiffness depends on the points' stress and
     * state: then the time step takes, for those materials, the largest
     * wave speed over their points (Simulator) and the others'
     * max_constant_wave_speed().
     */
    bool
    has_state_dependent_stiffness() const;

    /**
     * The largest kinematic viscosity eta / rho (m^2/s) of the materials'
     * models (MaterialModel::maximum_viscosity()): the explicit step's
     * viscous bound dt <= h^2 / (2 d nu). 0 if no model has one.
     */
    double
    max_kinematic_viscosity() const;

    /**
     * Whether a material bounds its points' volume ('Minimum density'
     * above 0): then the run's summary counts the stress updates that
     * kept a volume at the bound.
     */
    bool
    has_volume_bound() const;

    /**
     * Largest elastic wave speed of the materials whose stiffness does not
     * depend on the state; max_wave_speed() if there are only such.
     */
    double
    max_constant_wave_speed() const;

    /**
     * One point's stress update over a time step @p dt from its velocity
     * gradient @p grad_v (dim x dim; plane strain in 2D): the stress is
     * carried with the point's rotation (objective_stress_rate()) while
     * @p material's model adds the increment of the strain
     * sym(grad_v) dt, updating the point's @p state. Returns that strain
     * increment. The material-point driver updates stresses here, the MPM
     * step (PointUpdate) through update_stored_stress(), the same
     * arithmetic. @p cell_size: the size of the point's background cell
     * (MaterialModel::update_stress_in_cell()).
     */
    template <int dim>
    SymmetricTensor<2, 3>
    update_stress(const Material          &material,
                  const Tensor<2, dim>    &grad_v,
                  const double             dt,
                  SymmetricTensor<2, 3>   &stress,
                  const ArrayView<double> &state,
                  const double             cell_size) const
    {
      double stored[6];
      std::memcpy(stored, &stress.access_raw_entry(0), sizeof stored);
      const SymmetricTensor<2, 3> strain_increment = update_stored_stress<dim>(
        material, grad_v, dt, stored, state, cell_size);
      std::memcpy(&stress.access_raw_entry(0), stored, sizeof stored);
      return strain_increment;
    }

    /**
     * update_stress() of the stress stored at @p stored_stress (six numbers
     * in SymmetricTensor's order, as a material point keeps it), read from
     * there and written back: the last rotation stores its results there
     * directly (ObjectiveStressRate::rotate_and_store(): a copy of the
     * rotated tensor would stall on the store forwarding).
     */
    template <int dim>
    SymmetricTensor<2, 3>
    update_stored_stress(const Material          &material,
                         const Tensor<2, dim>    &grad_v,
                         const double             dt,
                         double                  *stored_stress,
                         const ArrayView<double> &state,
                         const double             cell_size) const
    {
      SymmetricTensor<2, 3> strain_increment;
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = a; b < dim; ++b)
          strain_increment[a][b] = 0.5 * dt * (grad_v[a][b] + grad_v[b][a]);
      SymmetricTensor<2, 3> stress;
      std::memcpy(&stress.access_raw_entry(0),
                  stored_stress,
                  6 * sizeof(double));
      // Half the step's rotation before the model's increment and half
      // after (Strang splitting): the increment is added in the step's
      // mid-point frame, second order in dt (one rotation before it would
      // be first order: doc/materials.md).
      const auto half_step = stress_rate.rotation<dim>(grad_v, 0.5 * dt);
      ObjectiveStressRate::rotate<dim>(stress, half_step);
      material.model->update_stress_in_cell(
        strain_increment, stress, state, dt, cell_size);
      ObjectiveStressRate::rotate_and_store<dim>(stress,
                                                 half_step,
                                                 stored_stress);
      return strain_increment;
    }

    /// How the points' stress follows their rotation ('Materials/Objective
    /// stress rate'), for every material.
    const ObjectiveStressRate &
    objective_stress_rate() const
    {
      return stress_rate;
    }

    /**
     * Set the strength of the frictional materials for the step that
     * starts at @p time: their c and tan(phi) divided by 'Strength
     * reduction factor' at that time (MaterialModel::set_strength_reduction();
     * the models are told only when the factor changes). Costs nothing
     * when the factor is the default 1.
     */
    void
    set_time(const double time);

    /// The strength reduction factor of the current step (1 by default).
    double
    strength_reduction_factor() const
    {
      return current_strength_reduction;
    }

    /// Whether 'Strength reduction factor' is given (not the constant 1).
    bool
    reduces_strength() const
    {
      return strength_reduction != nullptr;
    }

  private:
    std::vector<Material> materials;
    /// max_n_state_variables().
    unsigned int          n_state_slots = 0;
    ObjectiveStressRate   stress_rate;
    /// 'Strength reduction factor' as a function of t; null for "1".
    std::unique_ptr<FunctionParser<1>> strength_reduction;
    std::string                        strength_reduction_expression = "1";
    double                             current_strength_reduction    = 1;
  };
} // namespace MPM

#endif
