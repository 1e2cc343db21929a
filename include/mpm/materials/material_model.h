#ifndef mpm_materials_material_model_h
#define mpm_materials_material_model_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The interface of a constitutive model. A model maps a strain increment
   * (the symmetric part of dt * grad v at a material point) to a new stress,
   * using and updating the point's own state variables (n_state_variables()
   * doubles, e.g. accumulated plastic strain). Stress and strain are 3x3 in
   * every dimension, so 2D is plane strain. The class is not templated on
   * dim for that reason.
   *
   * Sign convention: tension positive.
   *
   * To add a model, write one .cc file with a class derived from this one
   * and register it at the end of that file with
   * MPM_REGISTER_MATERIAL_MODEL (see linear_elastic.cc); it then appears as
   * a choice of "Materials/<name>/Model" and its parameters in the
   * subsection of that name.
   */
  class MaterialModel
  {
  public:
    virtual ~MaterialModel() = default;

    /**
     * Read the parameters of this model; the handler is inside the model's
     * own subsection.
     */
    virtual void
    parse_parameters(ParameterHandler &prm) = 0;

    /**
     * Stress update for one point. @p strain_increment is the
     * symmetric velocity gradient times the time step @p time_step (which
     * rate-dependent models need to turn it into a strain rate; the others
     * ignore it).
     */
    virtual void
    update_stress(const SymmetricTensor<2, 3> &strain_increment,
                  SymmetricTensor<2, 3>       &stress,
                  const ArrayView<double>     &state,
                  const double                 time_step) const = 0;

    /**
     * The stress update of a point in a background cell of size
     * @p cell_size (m; the cell's shortest vertex distance), which is what
     * the MPM step calls. A model whose response must not depend on the
     * mesh although its deformation localises in bands about one cell wide
     * (a softening law regularised by the cell size) overrides it; the
     * others keep this default, update_stress().
     */
    virtual void
    update_stress_in_cell(const SymmetricTensor<2, 3> &strain_increment,
                          SymmetricTensor<2, 3>       &stress,
                          const ArrayView<double>     &state,
                          const double                 time_step,
                          const double                 cell_size) const
    {
      (void)cell_size;
      update_stress(strain_increment, stress, state, time_step);
    }

    /**
     * Stored elastic energy per unit volume for the given stress, used by
     * the energy statistics.
     */
    virtual double
    strain_energy_density(const SymmetricTensor<2, 3> &stress) const = 0;

    /**
     * The P-wave (constrained) modulus lambda + 2 mu: with the density it
     * gives the elastic wave speed of the CFL condition.
     */
    virtual double
    p_wave_modulus() const = 0;

    /**
     * Whether the P-wave modulus depends on the point's stress and state
     * (a pressure-dependent stiffness such as Cam-Clay's K = v p / kappa).
     * Then the time step takes the largest wave speed over the points of
     * the material (gathered in the stress update) rather than
     * p_wave_modulus(); the points of the other materials cost nothing.
     */
    virtual bool
    stiffness_depends_on_state() const
    {
      return false;
    }

    /**
     * The P-wave modulus at a point's @p stress and @p state variables;
     * p_wave_modulus() unless the model overrides
     * p_wave_modulus_at_state(). Not virtual itself, so that a model that
     * only overrides p_wave_modulus() does not hide it
     * (-Woverloaded-virtual).
     */
    double
    p_wave_modulus(const SymmetricTensor<2, 3>   &stress,
                   const ArrayView<const double> &state) const
    {
      return p_wave_modulus_at_state(stress, state);
    }

    /**
     * The largest dynamic viscosity (Pa s) the model's stress can carry: a
     * viscous stress 2 eta D computed from the step's strain rate is
     * stable only for steps below about rho h^2 / (2 d eta) (explicit
     * diffusion), which the time step then respects
     * (MaterialLibrary::max_kinematic_viscosity()). 0, the default: no
     * viscous stress that bounds the step (a Newtonian liquid's is far
     * below its sound speed's bound and is left out).
     */
    virtual double
    maximum_viscosity() const
    {
      return 0;
    }

    /**
     * Coefficient of earth pressure at rest used by the geostatic initial
     * stress when the user does not give one; for an elastic solid in
     * uniaxial strain nu / (1 - nu).
     */
    virtual double
    default_k0() const = 0;

    /**
     * Whether the model's strength is a Mohr-Coulomb strength (c, phi)
     * that set_strength_reduction() divides: 'Materials/Strength reduction
     * factor' acts on these models and leaves the others as they are.
     */
    virtual bool
    has_frictional_strength() const
    {
      return false;
    }

    /**
     * From now on, use the strength divided by @p factor
     * (FrictionalStrength::reduced(): tan(phi) / F, c / F); 1 restores the
     * given strength exactly. Called between steps, never during a stress
     * update, and only for a model that has_frictional_strength().
     */
    virtual void
    set_strength_reduction(const double factor)
    {
      (void)factor;
      Assert(false,
             ExcMessage("set_strength_reduction() called for a model "
                        "without a frictional strength."));
    }

    /**
     * A state variable that the model wants regularised by a non-local
     * average over the neighbouring points of its material (a softening
     * law whose strength would otherwise depend on the cell size through
     * the width of its shear bands). Before every stress update the MPM
     * step (NonlocalAveraging) writes into state variable @p nonlocal_variable
     * the value (1 - m) v + m v_avg, at least 0, where v is state variable
     * @p local_variable of the point, v_avg its average weighted by
     * volume and by (1 - r^2 / R^2)^2 over the points of the material
     * within @p radius R, and m the @p over_nonlocal_factor. The model
     * reads the regularised value and updates the local one.
     */
    struct NonlocalVariable
    {
      unsigned int local_variable       = 0;
      unsigned int nonlocal_variable    = 1;
      double       radius               = 0;
      double       over_nonlocal_factor = 1;
    };

    /**
     * The variable of a model regularised by a non-local average, or null
     * (the default: the model's points are updated from their own state
     * alone, and the step does no averaging for them).
     */
    virtual const NonlocalVariable *
    nonlocal_variable() const
    {
      return nullptr;
    }

    virtual unsigned int
    n_state_variables() const
    {
      return 0;
    }

    virtual std::vector<std::string>
    state_variable_names() const
    {
      return {};
    }

    virtual void
    initialize_state(const ArrayView<double> &state) const
    {
      (void)state;
    }

  protected:
    /**
     * What p_wave_modulus(stress, state) returns; models whose
     * stiffness_depends_on_state() override it.
     */
    virtual double
    p_wave_modulus_at_state(const SymmetricTensor<2, 3>   &stress,
                            const ArrayView<const double> &state) const
    {
      (void)stress;
      (void)state;
      return p_wave_modulus();
    }
  };


  /**
   * The registry of material models: each model file registers its name, a
   * function that declares its parameters and a function that creates it.
   */
  namespace MaterialModelFactory
  {
    using Declarer = std::function<void(ParameterHandler &)>;
    using Creator  = std::function<std::unique_ptr<MaterialModel>()>;

    /**
     * Called by MPM_REGISTER_MATERIAL_MODEL at program start.
     */
    bool
    register_model(const std::string &name,
                   const std::string &description,
                   const Declarer    &declare,
                   const Creator     &create);

    /**
     * Names joined by '|', for a Patterns::Selection.
     */
    std::string
    model_names();

    /**
     * Declare, for every registered model, its subsection (named like the
     * model) and its parameters.
     */
    void
    declare_parameters(ParameterHandler &prm);

    /**
     * Create the model called @p name and let it read its subsection.
     */
    std::unique_ptr<MaterialModel>
    create(const std::string &name, ParameterHandler &prm);
  } // namespace MaterialModelFactory
} // namespace MPM

/**
 * Register a material model class under a name shown in the parameter file.
 * The class needs a static declare_parameters(ParameterHandler &).
 */
#define MPM_CONCAT_IMPL(a, b) a##b
#define MPM_CONCAT(a, b) MPM_CONCAT_IMPL(a, b)
#define MPM_REGISTER_MATERIAL_MODEL(classname, name, description)         \
  namespace                                                               \
  {                                                                       \
    const bool MPM_CONCAT(mpm_material_model_registered_, __LINE__) =     \
      MPM::MaterialModelFactory::register_model(                          \
        name, description, &classname::declare_parameters, []() {         \
          return std::unique_ptr<MPM::MaterialModel>(                     \
            std::make_unique<classname>());                               \
        });                                                               \
  }

#endif
