#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/restart/checkpointing.h>

#include <boost/crc.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace MPM
{
  namespace
  {
    namespace fs = std::filesystem;

    double
    wall_seconds()
    {
      return std::chrono::duration<double>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
    }

    /**
     * CRC-32 of the file @p path, read in blocks.
     */
    std::uint32_t
    file_crc(const fs::path &path)
    {
      boost::crc_32_type crc;
      std::ifstream      in(path, std::ios::binary);
      std::vector<char>  buffer(1 << 20);
      while (in)
        {
          in.read(buffer.data(), buffer.size());
          crc.process_bytes(buffer.data(), in.gcount());
        }
      return crc.checksum();
    }

    const std::string manifest_header = "dealii-mpm checkpoint manifest 1";

    /**
     * Write the manifest of every file in @p folder, itself last and
     * through a temporary name, so that a manifest exists only for a
     * complete checkpoint.
     */
    void
    write_manifest(const fs::path &folder)
    {
      std::ostringstream manifest;
      manifest << manifest_header << '\n';
      for (const auto &entry : fs::directory_iterator(folder))
        if (entry.is_regular_file())
          manifest << entry.path().filename().string() << ' '
                   << entry.file_size() << ' ' << file_crc(entry.path())
                   << '\n';
      manifest << "end\n";
      {
        std::ofstream out(folder / "manifest.tmp");
        out << manifest.str();
        out.close();
        AssertThrow(out, ExcMessage("Could not write the checkpoint manifest " +
                                    (folder / "manifest.tmp").string()));
      }
      fs::rename(folder / "manifest.tmp", folder / "manifest");
    }

    /**
     * Check every file of @p folder's manifest; an empty string if all is
     * well, else what is wrong.
     */
    std::string
    check_manifest(const fs::path &folder)
    {
      std::ifstream in(folder / "manifest");
      std::string   line;
      if (!in || !std::getline(in, line) || line != manifest_header)
        return "The checkpoint " + folder.string() +
               " has no valid manifest: it was not completely written.";
      bool complete = false;
      while (std::getline(in, line))
        {
          if (line == "end")
            {
              complete = true;
              break;
            }
          std::istringstream entry(line);
          std::string        name;
          std::uintmax_t     size = 0;
          std::uint32_t      crc  = 0;
          entry >> name >> size >> crc;
          const fs::path file = folder / name;
          if (!fs::exists(file))
            return "The checkpoint file " + file.string() + " is missing.";
          if (fs::file_size(file) != size)
            return "The checkpoint file " + file.string() + " has " +
                   std::to_string(fs::file_size(file)) +
                   " bytes, its manifest says " + std::to_string(size) +
                   ": the checkpoint is truncated or damaged.";
          if (file_crc(file) != crc)
            return "The checkpoint file " + file.string() +
                   " does not match the checksum in its manifest: the "
                   "checkpoint is damaged.";
        }
      if (!complete)
        return "The manifest of the checkpoint " + folder.string() +
               " is incomplete: the checkpoint is damaged.";
      return "";
    }
  } // namespace


  template <int dim>
  void
  Checkpointing<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Checkpointing");
    prm.declare_entry("Steps between checkpoints",
                      "0",
                      Patterns::Integer(0),
                      "Write a checkpoint (folder 'checkpoint' in the output "
                      "directory) every this many steps; 0 = never.");
    prm.declare_entry("Minutes between checkpoints",
                      "0",
                      Patterns::Double(0),
                      "Write a checkpoint whenever this much wall time has "
                      "passed since the last one; 0 = never.");
    prm.declare_entry("Stop after steps",
                      "0",
                      Patterns::Integer(0),
                      "Write a checkpoint and stop after this many steps of "
                      "this invocation (e.g. to fit a batch job's time "
                      "limit; resume with 'Resume from checkpoint = true'); "
                      "0 = run to the end time.");
    prm.declare_entry("Resume from checkpoint",
                      "false",
                      Patterns::Bool(),
                      "Continue the run from the last checkpoint in the "
                      "output directory instead of starting it. The "
                      "parameters must describe the same scene (mesh, "
                      "materials, postprocessors); the end time may be "
                      "changed.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Checkpointing<dim>::parse_parameters(ParameterHandler  &prm,
                                       const std::string &output_directory)
  {
    directory = output_directory;
    prm.enter_subsection("Checkpointing");
    step_interval    = prm.get_integer("Steps between checkpoints");
    minutes_interval = prm.get_double("Minutes between checkpoints");
    stop_after_steps = prm.get_integer("Stop after steps");
    resume_run       = prm.get_bool("Resume from checkpoint");
    prm.leave_subsection();
    last_checkpoint_wall_time = wall_seconds();
  }


  template <int dim>
  bool
  Checkpointing<dim>::due(const unsigned int steps_this_run,
                          const MPI_Comm     comm)
  {
    bool write = stop_requested(steps_this_run) ||
                 (step_interval > 0 && steps_this_run % step_interval == 0);
    if (minutes_interval > 0)
      {
        // Rank 0's clock decides: every rank must take part in the write.
        const bool late =
          wall_seconds() - last_checkpoint_wall_time >= 60 * minutes_interval;
        write = write || Utilities::MPI::broadcast(comm, late, 0);
      }
    if (write)
      last_checkpoint_wall_time = wall_seconds();
    return write;
  }


  template <int dim>
  std::size_t
  Checkpointing<dim>::write(
    const parallel::distributed::Triangulation<dim> &triangulation,
    Particles::ParticleHandler<dim>                 &particle_handler,
    const std::vector<std::string>                  &point_slots,
    const std::string                               &state) const
  {
    const MPI_Comm comm     = triangulation.get_communicator();
    const bool     is_root  = Utilities::MPI::this_mpi_process(comm) == 0;
    const fs::path current  = fs::path(directory) / "checkpoint";
    const fs::path fresh    = fs::path(directory) / "checkpoint.new";
    const fs::path previous = fs::path(directory) / "checkpoint.old";

    if (is_root)
      {
        fs::remove_all(fresh);
        fs::create_directories(fresh);
      }
    MPI_Barrier(comm);

    particle_handler.prepare_for_serialization();
    triangulation.save((fresh / "mesh").string());

    std::size_t bytes = 0;
    if (is_root)
      {
        {
          std::ofstream out(fresh / "state", std::ios::binary);
          out << state;
          out.close();
          AssertThrow(out,
                      ExcMessage("Could not write the checkpoint state " +
                                 (fresh / "state").string()));
        }
        {
          std::ofstream out(fresh / "point_slots");
          for (const std::string &name : point_slots)
            out << name << '\n';
          out.close();
          AssertThrow(out,
                      ExcMessage("Could not write the checkpoint's slots " +
                                 (fresh / "point_slots").string()));
        }
        write_manifest(fresh);
        // The complete new checkpoint replaces the old one.
        fs::remove_all(previous);
        if (fs::exists(current))
          fs::rename(current, previous);
        fs::rename(fresh, current);
        fs::remove_all(previous);
        for (const auto &entry : fs::directory_iterator(current))
          bytes += entry.file_size();
      }
    MPI_Barrier(comm);
    return Utilities::MPI::broadcast(comm, bytes, 0);
  }


  template <int dim>
  std::string
  Checkpointing<dim>::folder_to_resume_from() const
  {
    for (const char *name : {"checkpoint", "checkpoint.old"})
      if (fs::exists(fs::path(directory) / name / "manifest"))
        return (fs::path(directory) / name).string();
    return "";
  }


  template <int dim>
  std::string
  Checkpointing<dim>::read(
    parallel::distributed::Triangulation<dim> &triangulation,
    Particles::ParticleHandler<dim>           &particle_handler,
    const std::vector<std::string>            &point_slots) const
  {
    const MPI_Comm comm = triangulation.get_communicator();
    // Rank 0 checks, every rank learns the verdict.
    std::string folder, problem;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        folder = folder_to_resume_from();
        if (folder.empty())
          problem = "Checkpointing/Resume from checkpoint = true, but " +
                    directory +
                    " holds no complete checkpoint (a folder 'checkpoint' "
                    "with its manifest). Set 'Output/Directory' to the "
                    "output directory of the run to resume.";
        else
          problem = check_manifest(folder);
        // Checkpoints written before the slots were recorded have no
        // such file: read as they are.
        std::ifstream slots_file(fs::path(folder) / "point_slots");
        if (problem.empty() && slots_file)
          {
            std::vector<std::string> written;
            for (std::string name; std::getline(slots_file, name);)
              written.push_back(name);
            if (written != point_slots)
              problem =
                "The points of the checkpoint " + folder + " have " +
                std::to_string(written.size()) +
                " property slots, the parameters of this run lay out " +
                std::to_string(point_slots.size()) +
                " (a parameter that adds or removes point data, e.g. the "
                "transfer scheme or 'Pore water/Pressure rate averaging', "
                "differs from the checkpointed run's): resume with the "
                "parameters of that run.";
          }
      }
    folder  = Utilities::MPI::broadcast(comm, folder, 0);
    problem = Utilities::MPI::broadcast(comm, problem, 0);
    if (!problem.empty())
      throw InputError(problem);

    triangulation.load(folder + "/mesh");
    particle_handler.deserialize();

    std::ifstream      in(folder + "/state", std::ios::binary);
    std::ostringstream state;
    state << in.rdbuf();
    return state.str();
  }


  template class Checkpointing<2>;
  template class Checkpointing<3>;
} // namespace MPM
