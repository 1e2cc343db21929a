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

    /// The subsection 'Material point driver'.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Reads its subsection, 'Materials' and 'Output/Directory'.
    void
    parse_parameters(ParameterHandler &prm);

    /// Runs the path and writes the curve and the report.
    void
    run() const;

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
    unsigned int    n_cycles       = 1;
    double          confining_pressure = 0;
    double          duration           = 1;
    std::string     directory;
  };
} // namespace MPM

#endif
