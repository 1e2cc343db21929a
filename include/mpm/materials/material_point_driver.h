#ifndef mpm_materials_material_point_driver_h
#define mpm_materials_material_point_driver_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/material_library.h>

#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The material-point driver (`mpm --material-point-driver case.prm`):
   * one material point of a registered model taken along a prescribed
   * strain or mixed strain-stress path, through the same stress update as
   * the MPM step (MaterialLibrary::update_stress(): the objective rotation,
   * then the model). What a researcher runs to calibrate a model before a
   * slope, and what the element tests of the models use.
   *
   * Paths (compression negative, as everywhere in the code; the axial
   * direction is y):
   * - 'simple shear': v_x = gamma_dot y, to the shear strain 'Final strain';
   * - 'cyclic simple shear': the same, gamma going 0 -> +A -> -A -> 0 in
   *   each of 'Cycles' cycles (A = 'Final strain');
   * - 'oedometer': axial compression with no lateral strain;
   * - 'undrained triaxial': axial compression at constant volume (the
   *   lateral strain rate is half the axial one, of opposite sign);
   * - 'drained triaxial': axial compression with the lateral stresses held
   *   at the confining pressure (the lateral strain found by a secant
   *   iteration each step).
   * The point starts from the isotropic stress -'Confining pressure' I.
   *
   * Writes OUTPUT/stress_strain.csv (one row per step: the path's strain,
   * volumetric strain, stresses, p, q, the model's state variables) and
   * OUTPUT/report.txt (the final state, and for simple shear the deviation
   * from the closed form of a hypoelastic body, Dienes 1979).
   *
   * A model's unit test builds a driver with from_text() and compares the
   * History of run_path() with the model's closed form.
   */
  class MaterialPointDriver
  {
  public:
    enum class Path
    {
      simple_shear,
      cyclic_simple_shear,
      oedometer,
      undrained_triaxial,
      drained_triaxial
    };

    /// The point's state after one step of the path.
    struct Record
    {
      unsigned int step = 0;
      double       time = 0;
      /// The path's own strain (gamma, or the axial compressive strain).
      double path_strain = 0;
      /// The sum of the traces of the strain increments.
      double volumetric_strain = 0;
      /// The sum of the strain increments sym(L) dt (compression negative).
      SymmetricTensor<2, 3> strain;
      SymmetricTensor<2, 3> stress;
      /// The model's state variables (state_variable_names()).
      std::vector<double> state;
    };

    /// What run_path() gives back.
    struct History
    {
      /// Step 0 (the initial state) to the last step.
      std::vector<Record> records;
      /// The initial shear modulus, probed by a small shear increment.
      double shear_modulus = 0;
      /// 'drained triaxial': the most iterations one step's lateral strain
      /// needed.
      unsigned int max_iterations = 0;
    };

    /// The subsection 'Material point driver'.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Reads its subsection, 'Materials' and 'Output/Directory'.
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * A driver read from the text of a parameter file that sets
     * 'Materials' and 'Material point driver' (the two passes of the mpm
     * executable: the list of materials first), writing to
     * @p output_directory. For unit tests.
     */
    static MaterialPointDriver
    from_text(const std::string &parameters,
              const std::string &output_directory = ".");

    /// Runs the path and gives back every step's state; writes nothing.
    History
    run_path() const;

    /// Runs the path and writes the curve and the report.
    void
    run() const;

    /// The material the point is made of.
    const Material &
    material() const
    {
      return materials[material_index];
    }

  private:
    /// The velocity gradient of step @p n of the strain-controlled paths
    /// (the lateral part of 'drained triaxial' is found in run()).
    Tensor<2, 3>
    velocity_gradient(const unsigned int n, const double dt) const;

    /// The path's own strain after step @p n (gamma or the axial strain).
    double
    path_strain(const unsigned int n) const;

    MaterialLibrary materials;
    unsigned int    material_index = 0;
    Path            path           = Path::simple_shear;
    double          final_strain   = 0.1;
    unsigned int    n_steps        = 1000;
    /// 'Cell size' (0: no cell).
    double          cell_size      = 0;
    unsigned int    n_cycles       = 1;
    double          confining_pressure = 0;
    double          duration           = 1;
    std::string     directory;
  };
} // namespace MPM

#endif
