#ifndef mpm_boundary_conditions_boundary_spec_h
#define mpm_boundary_conditions_boundary_spec_h

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <mpm/boundary_conditions/basal_law.h>

#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /// The kinds of boundary ('Boundary conditions/NAME/Type').
  enum class BoundaryType
  {
    /// No constraint.
    free,
    /// Zero velocity (no-slip).
    fixed,
    /// Zero normal velocity, free tangential velocity.
    slip,
    /// Unilateral contact with a basal law on the tangential velocity.
    friction,
    /// Prescribed (normal, tangential) velocity in the node frame (2D).
    velocity,
    /// No constraint; a load, the 'Traction' (SurfaceTractions).
    traction,
    /// No constraint; a viscous dashpot that absorbs the waves arriving
    /// at the boundary (AbsorbingBoundaries), and the 'Traction'.
    absorbing
  };

  /// Whether a boundary of type @p type holds the material's velocity
  /// (a wall), rather than leaving it free.
  inline bool
  is_wall(const BoundaryType type)
  {
    return type != BoundaryType::free && type != BoundaryType::traction &&
           type != BoundaryType::absorbing;
  }


  /// Whether a boundary of type @p type takes a 'Traction' (a load on
  /// its faces): traction and absorbing boundaries.
  inline bool
  carries_traction(const BoundaryType type)
  {
    return type == BoundaryType::traction || type == BoundaryType::absorbing;
  }


  /**
   * One named boundary of the parameter file: the mesh boundary ids it
   * covers, its type, its normal and, for Type = friction, its basal law.
   */
  template <int dim>
  struct BoundarySpec
  {
    std::string                     name;
    std::vector<types::boundary_id> ids;
    BoundaryType                    type = BoundaryType::free;
    /// The basal law (Type = friction only, else nullptr).
    std::shared_ptr<const BasalLaw<dim>> law;
    bool                            normal_from_mesh = true;
    /// Unit outward normal for 'Normal = given' (the scene's frame).
    Tensor<1, dim>                  given_normal;
    /// (normal, tangential) velocity for Type = velocity.
    Tensor<1, dim>                  local_velocity;
    /// Force per area (Pa) for Type = traction or absorbing, in the
    /// scene's frame.
    Tensor<1, dim>                  traction;
    /// Type = absorbing: the dashpots' impedances rho c_p (normal) and
    /// rho c_s (tangential), in Pa s/m.
    double normal_impedance     = 0;
    double tangential_impedance = 0;
    /// Type = absorbing: the velocity of the wave coming in through the
    /// boundary, a function of t with dim components in the scene's frame
    /// ('Absorbing input velocity'), or empty for none.
    std::string input_velocity;
    /// 'Drainage = drained': pore water passes through this wall (its
    /// normal velocity is free there, the pore pressure zero).
    bool                            drained = false;
    /// 'Pore pressure': the pressure (Pa) of the water this boundary
    /// drains into, a function of the scene's x, y (, z) and t, or empty
    /// for none (a drained boundary at p = 0). BoundaryPorePressures.
    std::string                     pore_pressure;
  };
} // namespace MPM

#endif
