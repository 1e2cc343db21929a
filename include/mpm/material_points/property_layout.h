#ifndef mpm_material_points_property_layout_h
#define mpm_material_points_property_layout_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <cstring>
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
   * components in every dimension, because plane strain has a non-zero
   * sigma_zz that plasticity models need, in the order in which
   * SymmetricTensor<2, 3> stores them (xx, yy, zz, xy, xz, yz; see
   * read_symmetric_tensor()). Files the user reads or writes (point files,
   * text output) use the Voigt order of voigt_index instead.
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
   * Voigt order (xx, yy, zz, xy, yz, xz) of the six components in the files
   * the user reads and writes: the stress columns of a point file and of
   * the text output.
   */
  constexpr unsigned int voigt_index[6][2] = {{0, 0},
                                              {1, 1},
                                              {2, 2},
                                              {0, 1},
                                              {1, 2},
                                              {0, 2}};

  /**
   * The symmetric tensor stored at @p data (six values in SymmetricTensor's
   * own order). One block copy: the stress update reads a point's stress
   * this way and passes it to the material model, which copies it as a
   * whole; built entry by entry (as from Voigt's order), its 8-byte stores
   * could not be forwarded to the model's 16-byte loads, a stall measured
   * at a tenth of the Mohr-Coulomb update's time in the flume.
   */
  static_assert(sizeof(SymmetricTensor<2, 3>) == 6 * sizeof(double) &&
                  SymmetricTensor<2, 3>::component_to_unrolled_index(
                    TableIndices<2>(0, 2)) == 4 &&
                  SymmetricTensor<2, 3>::component_to_unrolled_index(
                    TableIndices<2>(1, 2)) == 5,
                "The stored order of stress and strain (and the names in "
                "PropertyLayout::fixed_names()) assume deal.II's order "
                "xx, yy, zz, xy, xz, yz of six contiguous values.");

  inline SymmetricTensor<2, 3>
  read_symmetric_tensor(const double *data)
  {
    SymmetricTensor<2, 3> t;
    std::memcpy(&t.access_raw_entry(0), data, 6 * sizeof(double));
    return t;
  }

  /**
   * Store @p t at @p data; the inverse of read_symmetric_tensor().
   */
  inline void
  write_symmetric_tensor(const SymmetricTensor<2, 3> &t, double *data)
  {
    std::memcpy(data, &t.access_raw_entry(0), 6 * sizeof(double));
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
      // SymmetricTensor's order (read_symmetric_tensor()).
      for (const std::string c : {"xx", "yy", "zz", "xy", "xz", "yz"})
        names.push_back(prefix + c);
    names.emplace_back("material_id");
    return names;
  }
} // namespace MPM

#endif
