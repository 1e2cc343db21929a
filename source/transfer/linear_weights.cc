// The mesh's own linear weights: the points grouped by their cells and
// their shape functions (prepare()); the passes are ParticleGridPasses'.

#include <deal.II/base/tensor.h>

#include <mpm/parallel/thread_chunks.h>
#include <mpm/transfer/linear_weights.h>
#include <mpm/transfer/particle_grid_passes.templates.h>

#include <iterator>

namespace MPM
{
  template <int dim>
  LinearWeights<dim>::LinearWeights(Simulator<dim> &simulator,
                                    ParameterHandler &)
      : ParticleGridPasses<dim, LinearWeights<dim>>(simulator)
  {}


  template <int dim>
  double
  LinearWeights<dim>::prepare()
  {
    auto              &particle_handler = this->get_mutable_particle_handler();
    TimerOutput::Scope t(this->get_timer(), "shape functions");
    this->clear_active_cells();
    this->shape_functions.resize(particle_handler.n_locally_owned_particles());
    this->points.resize(particle_handler.n_locally_owned_particles());

    // The cells holding points, in the order of the points (the
    // ParticleHandler's, cell by cell); each cell's points are its entries.
    for (auto it = particle_handler.begin(); it != particle_handler.end();)
      {
        const typename Triangulation<dim>::active_cell_iterator cell =
          it->get_surrounding_cell();
        const auto points = particle_handler.particles_in_cell(cell);
        // Counted along the range at hand: n_particles_in_cell() would
        // look the cell up again.
        this->add_active_cell(cell->active_cell_index(),
                              static_cast<unsigned int>(
                                std::distance(points.begin(), points.end())),
                              points.begin());
        it = points.end();
      }
    const double shortest_edge = this->finish_active_cells();
    // Their shape functions, cell by cell on the available threads, with
    // the cell's geometry as the shape functions take it: its bilinear map
    // in 2D; in 3D its affine map if it is a parallelepiped (a constant
    // Jacobian), its vertices otherwise.
    for_each_chunk(
      this->active_cells.size(),
      this->cell_chunk_size,
      [this](const unsigned int, const unsigned int first, const unsigned int last) {
        for (unsigned int c = first; c < last; ++c)
          {
            const auto        &cell  = this->active_cells[c];
            auto               point = cell.first_point;
            const unsigned int end   = cell.first_entry + cell.n_points;
            for (unsigned int k = cell.first_entry; k < end; ++k, ++point)
              {
                this->points[k] = point->get_properties().data();
                if constexpr (dim == 2)
                  this->shape_functions[k].reinit(
                    *cell.map, point->get_reference_location());
                else if (cell.parallelepiped)
                  this->shape_functions[k].reinit(
                    *cell.parallelepiped, point->get_reference_location());
                else
                  this->shape_functions[k].reinit(
                    *cell.vertices, point->get_reference_location());
              }
          }
      });
    return shortest_edge;
  }


  template class ParticleGridPasses<2, LinearWeights<2>>;
  template class ParticleGridPasses<3, LinearWeights<3>>;
  template class LinearWeights<2>;
  template class LinearWeights<3>;
} // namespace MPM

MPM_REGISTER_PARTICLE_GRID_WEIGHTS(MPM::LinearWeights,
                                   "linear",
                                   "the mesh's bilinear functions at the point.")
