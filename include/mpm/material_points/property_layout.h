#ifndef mpm_material_points_property_layout_h
#define mpm_material_points_property_layout_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Where each quantity of a material point lives in the property array that
   * Particles::ParticleHandler stores for it. Every point has the fixed
   * slots below; the state variables of its material model (e.g. plastic
   * strain) follow at `state`. Stress and strain are stored with all six
   * components (xx, yy, zz, xy, yz, xz) in every dimension, because plane
   * strain has a non-zero sigma_zz that plasticity models need.
   */
  template <int dim>
  struct PropertyLayout
  {
    static constexpr unsigned int mass        = 0;
    static constexpr unsigned int volume      = 1;
    static constexpr unsigned int velocity    = 2;
    static constexpr unsigned int stress      = velocity + dim;
    static constexpr unsigned int strain      = stress + 6;
    static constexpr unsigned int material_id = strain + 6;
    static constexpr unsigned int state       = material_id + 1;

    /**
     * Names of the fixed slots, in order, as written to the output files.
     */
    static std::vector<std::string>
    fixed_names();
  };

  /**
   * Voigt order of the six stored components.
   */
  constexpr unsigned int voigt_index[6][2] = {{0, 0},
                                              {1, 1},
                                              {2, 2},
                                              {0, 1},
                                              {1, 2},
                                              {0, 2}};

  inline SymmetricTensor<2, 3>
  read_symmetric_tensor(const double *data)
  {
    SymmetricTensor<2, 3> t;
    for (unsigned int k = 0; k < 6; ++k)
      t[voigt_index[k][0]][voigt_index[k][1]] = data[k];
    return t;
  }

  inline void
  write_symmetric_tensor(const SymmetricTensor<2, 3> &t, double *data)
  {
    for (unsigned int k = 0; k < 6; ++k)
      data[k] = t[voigt_index[k][0]][voigt_index[k][1]];
  }

  template <int dim>
  inline Tensor<1, dim>
  read_vector(const double *data)
  {
    Tensor<1, dim> v;
    for (unsigned int d = 0; d < dim; ++d)
      v[d] = data[d];
    return v;
  }

  template <int dim>
  std::vector<std::string>
  PropertyLayout<dim>::fixed_names()
  {
    std::vector<std::string> names = {"mass", "volume"};
    for (unsigned int d = 0; d < dim; ++d)
      names.emplace_back("velocity");
    for (const std::string prefix : {"stress_", "strain_"})
      for (const std::string c : {"xx", "yy", "zz", "xy", "yz", "xz"})
        names.push_back(prefix + c);
    names.emplace_back("material_id");
    return names;
  }
} // namespace MPM

#endif
