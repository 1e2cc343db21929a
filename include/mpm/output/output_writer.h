#ifndef mpm_output_output_writer_h
#define mpm_output_output_writer_h

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/grid/background_grid.h>
#include <mpm/materials/material_library.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Writes what a user opens in ParaView: the mesh once (mesh.pvtu, with
   * material and boundary information), the material points with all their
   * properties at every output time (particles-NNNNN.pvtu, indexed by
   * particles.pvd), in the output directory.
   */
  template <int dim>
  class OutputWriter
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Create the output directory (InputError if that fails).
     */
    void
    initialize(const MPI_Comm comm) const;

    const std::string &
    directory() const
    {
      return output_directory;
    }

    /**
     * Is it time for output at @p time (always at the first and last step)?
     */
    bool
    output_due(const double time, const double dt, const double end_time) const;

    void
    mark_written(const double time);

    void
    write_mesh(const BackgroundGrid<dim> &grid) const;

    void
    write_particles(const Particles::ParticleHandler<dim> &particle_handler,
                    const std::vector<std::string>        &property_names,
                    const double                           time,
                    const unsigned int                     output_index,
                    const MPI_Comm                         comm);

    /**
     * If 'Output/Write point file' is set: every point as a line of
     * points_end.txt (position and stress in the scene's frame, the volume
     * its mass had at the material's density), which a later run reads
     * with 'Type = file' and 'Initial stress = file'. One file, written by
     * rank 0 in the order of the point ids.
     */
    void
    write_point_file(const Particles::ParticleHandler<dim> &particle_handler,
                     const MaterialLibrary                 &materials,
                     const BackgroundGrid<dim>             &grid,
                     const MPI_Comm                         comm) const;

    bool
    particles_enabled() const
    {
      return write_particle_files;
    }

    double
    progress_interval() const
    {
      return progress_seconds;
    }

    /**
     * What the writer remembers of the run (the last output time, the
     * records of particles.pvd), for checkpoints.
     */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      ar &last_output_time &pvd_records &xdmf_entries;
    }

  private:
    std::string                               output_directory = "output";
    double                                    output_interval  = 0.1;
    bool                                      write_particle_files = true;
    bool                                      write_mesh_file      = true;
    bool                                      write_point_file_at_end = false;
    double                                    progress_seconds     = 10;
    double                                    last_output_time     = -1e300;
    std::vector<std::pair<double, std::string>> pvd_records;
    bool                                      hdf5 = false;
    std::vector<XDMFEntry>                    xdmf_entries;
  };
} // namespace MPM

#endif
