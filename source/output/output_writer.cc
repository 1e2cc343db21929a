#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>

#include <deal.II/numerics/data_out.h>

#include <deal.II/particles/data_out.h>

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/output/output_writer.h>
#include <mpm/solver/time_stepping.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

#include <filesystem>

namespace MPM
{
  template <int dim>
  void
  OutputWriter<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    {
      prm.declare_entry("Directory",
                        "output",
                        Patterns::DirectoryName(),
                        "Directory for all output (created if missing), "
                        "relative to where mpm is started.");
      prm.declare_entry("Output interval",
                        "0.1",
                        Patterns::Double(0),
                        "Simulated time between two outputs (particle files "
                        "and a line of the statistics file), in s; 0 means "
                        "every step.");
      prm.declare_entry("Write particles",
                        "true",
                        Patterns::Bool(),
                        "Write the material points (VTU/PVD) at output "
                        "times.");
      prm.declare_entry("Particle format",
                        "vtu",
                        Patterns::Selection("vtu|hdf5"),
                        "File format of the material points: 'vtu' (one "
                        ".vtu per rank and a .pvtu per output time, "
                        "particles.pvd for ParaView) or 'hdf5' (one "
                        "particles_NNNNN.h5 per output time written by all "
                        "ranks together, particles.xdmf for ParaView; for "
                        "large runs: one file per step whatever the number "
                        "of ranks). The .h5 files are larger: they hold "
                        "doubles, uncompressed (the column collapse's first "
                        "output: 974 kB against 39 kB of zlib-compressed "
                        ".vtu and .pvtu).");
      prm.declare_entry("Write mesh",
                        "true",
                        Patterns::Bool(),
                        "Write the background mesh once (mesh_0.pvtu).");
      prm.declare_entry("Write point file",
                        "false",
                        Patterns::Bool(),
                        "At the end of the run, write points_end.txt: one "
                        "line per point with its coordinates, volume and six "
                        "stress components (xx yy zz xy yz xz), the format "
                        "of 'Material points/.../Point file' with 'Initial "
                        "stress = file', so that a later run can start from "
                        "this run's stress state.");
      prm.declare_entry("Progress interval",
                        "10",
                        Patterns::Double(0),
                        "Wall-clock seconds between two progress lines on "
                        "the screen.");
    }
    prm.leave_subsection();
  }


  template <int dim>
  void
  OutputWriter<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    {
      output_directory     = prm.get("Directory");
      output_interval      = prm.get_double("Output interval");
      write_particle_files = prm.get_bool("Write particles");
      write_mesh_file      = prm.get_bool("Write mesh");
      write_point_file_at_end = prm.get_bool("Write point file");
      hdf5                 = prm.get("Particle format") == "hdf5";
      progress_seconds     = prm.get_double("Progress interval");
    }
    prm.leave_subsection();
    if (output_directory.empty())
      output_directory = ".";
    if (output_directory.back() != '/')
      output_directory += '/';
  }


  template <int dim>
  void
  OutputWriter<dim>::initialize(const MPI_Comm comm) const
  {
    bool ok = true;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::error_code ec;
        std::filesystem::create_directories(output_directory, ec);
        ok = std::filesystem::is_directory(output_directory);
      }
    ok = Utilities::MPI::broadcast(comm, ok, 0);
    check_input(ok,
                "Cannot create the output directory '" + output_directory +
                  "' (parameter 'Output/Directory').");
  }


  template <int dim>
  bool
  OutputWriter<dim>::output_due(const double time,
                                const double dt,
                                const double end_time) const
  {
    (void)dt;
    return time >= effective_end_time(end_time) ||
           time >= last_output_time + output_interval * (1 - 1e-9);
  }


  template <int dim>
  void
  OutputWriter<dim>::mark_written(const double time)
  {
    last_output_time = time;
  }


  template <int dim>
  void
  OutputWriter<dim>::write_mesh(const BackgroundGrid<dim> &grid) const
  {
    if (!write_mesh_file)
      return;
    DataOut<dim> data_out;
    data_out.attach_triangulation(grid.triangulation);
    Vector<float> material_id(grid.triangulation.n_active_cells());
    Vector<float> subdomain(grid.triangulation.n_active_cells());
    for (const auto &cell : grid.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          material_id[cell->active_cell_index()] = cell->material_id();
          subdomain[cell->active_cell_index()]   = cell->subdomain_id();
        }
    data_out.add_data_vector(material_id, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(grid.mapping);
    data_out.write_vtu_with_pvtu_record(
      output_directory, "mesh", 0, grid.triangulation.get_communicator(), 0);
  }


  template <int dim>
  void
  OutputWriter<dim>::write_point_file(
    const Particles::ParticleHandler<dim> &particle_handler,
    const MaterialLibrary                 &materials,
    const BackgroundGrid<dim>             &grid,
    const MPI_Comm                         comm) const
  {
    if (!write_point_file_at_end)
      return;
    using Layout = PropertyLayout<dim>;
    std::vector<std::pair<types::particle_index, std::string>> lines;
    for (const auto &point : particle_handler)
      {
        const auto props = point.get_properties();
        const auto &material =
          materials[static_cast<unsigned int>(props[Layout::material_id])];
        std::ostringstream line;
        line << std::setprecision(17);
        const Point<dim> x = grid.to_scene_frame(point.get_location());
        for (unsigned int d = 0; d < dim; ++d)
          line << x[d] << ' ';
        // The volume of the point's mass at the material's density: the
        // next run's mass is then exactly this run's.
        line << props[Layout::mass] / material.density;
        const SymmetricTensor<2, 3> stress =
          grid.to_scene_frame(read_symmetric_tensor(&props[Layout::stress]));
        for (unsigned int k = 0; k < 6; ++k)
          line << ' ' << stress[voigt_index[k][0]][voigt_index[k][1]];
        lines.emplace_back(point.get_id(), line.str());
      }
    const auto all = Utilities::MPI::gather(comm, lines, 0);
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::vector<std::pair<types::particle_index, std::string>> sorted;
    for (const auto &rank_lines : all)
      sorted.insert(sorted.end(), rank_lines.begin(), rank_lines.end());
    std::sort(sorted.begin(), sorted.end());
    const std::string name = output_directory + "points_end.txt";
    std::ofstream     out(name + ".new");
    out << "# dealii-mpm point file: " << dim
        << " coordinates (m), volume (m^3), stress xx yy zz xy yz xz (Pa); "
           "read it with 'Type = file' and 'Initial stress = file'\n";
    for (const auto &l : sorted)
      out << l.second << '\n';
    out.close();
    AssertThrow(out, ExcMessage("Could not write " + name + ".new"));
    std::filesystem::rename(name + ".new", name);
  }


  template <int dim>
  void
  OutputWriter<dim>::write_particles(
    const Particles::ParticleHandler<dim> &particle_handler,
    const std::vector<std::string>        &property_names,
    const double                           time,
    const unsigned int                     output_index,
    const MPI_Comm                         comm)
  {
    if (!write_particle_files)
      return;
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      interpretation(property_names.size(),
                     DataComponentInterpretation::component_is_scalar);
    // A name given to dim consecutive properties is a vector (velocity,
    // the pore water's water_velocity): ParaView then shows one vector
    // field with its magnitude, not dim scalars of the same name.
    for (unsigned int i = 0; i + dim <= property_names.size();)
      {
        unsigned int run = 1;
        while (i + run < property_names.size() &&
               property_names[i + run] == property_names[i])
          ++run;
        if (run == dim)
          for (unsigned int c = 0; c < dim; ++c)
            interpretation[i + c] =
              DataComponentInterpretation::component_is_part_of_vector;
        i += run;
      }

    Particles::DataOut<dim> data_out;
    data_out.build_patches(particle_handler, property_names, interpretation);
    // deal.II compresses with zlib's best_compression by default: 3 % of
    // the flume's run time for files 10 % smaller than with best_speed.
    data_out.set_flags(DataOutBase::VtkFlags(
      time, output_index, true, DataOutBase::VtkFlags::best_speed));
    if (hdf5)
      {
        // Positions and data in one file per output time, which all ranks
        // write together; the XDMF file tells ParaView what is in them.
        DataOutBase::DataOutFilter filter(
          DataOutBase::DataOutFilterFlags(false, true));
        data_out.write_filtered_data(filter);
        const std::string file =
          "particles_" + Utilities::int_to_string(output_index, 5) + ".h5";
        data_out.write_hdf5_parallel(filter, output_directory + file, comm);
        xdmf_entries.push_back(
          data_out.create_xdmf_entry(filter, file, time, comm));
        data_out.write_xdmf_file(xdmf_entries,
                                 output_directory + "particles.xdmf",
                                 comm);
        return;
      }
    const std::string file = data_out.write_vtu_with_pvtu_record(
      output_directory,
      "particles",
      output_index,
      comm,
      5);
    pvd_records.emplace_back(time, file);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ofstream pvd(output_directory + "particles.pvd");
        DataOutBase::write_pvd_record(pvd, pvd_records);
      }
  }


  template class OutputWriter<2>;
  template class OutputWriter<3>;
} // namespace MPM
