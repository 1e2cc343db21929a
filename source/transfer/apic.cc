#include <mpm/transfer/apic.h>
#include <mpm/transfer/particle_grid_weights.h>

namespace MPM
{
  template <int dim>
  Apic<dim>::Apic(ParameterHandler &prm)
    : limit_affine_energy(prm.get_bool("APIC energy limit"))
  {}


  template <int dim>
  std::vector<std::string>
  Apic<dim>::point_property_names() const
  {
    std::vector<std::string> names;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = 0; b < dim; ++b)
        names.push_back(std::string("affine_") + "xyz"[a] + "xyz"[b]);
    names.emplace_back("affine_energy");
    if (dim == 2)
      names.emplace_back("affine_spin_z");
    else
      for (unsigned int a = 0; a < dim; ++a)
        names.push_back(std::string("affine_spin_") + "xyz"[a]);
    return names;
  }


  template <int dim>
  void
  Apic<dim>::initialize_points(const ParticleGridWeights<dim> &weights,
                               const unsigned int              first_slot) const
  {
    std::vector<Tensor<2, dim>> second_moments;
    weights.second_moments(second_moments);
    const auto &points = weights.point_properties();
    for (unsigned int p = 0; p < points.size(); ++p)
      {
        double *affine = points[p] + first_slot;
        store_affine(stored_affine(affine), second_moments[p], affine);
      }
  }


  template class Apic<2>;
  template class Apic<3>;
} // namespace MPM

MPM_REGISTER_TRANSFER_SCHEME(MPM::Apic,
                             "apic",
                             "affine particle-in-cell (Jiang et al. 2015): "
                             "points carry an affine velocity field that "
                             "particle-to-grid keeps exactly.")
