#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/physics/transformations.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/terrain.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace MPM
{
  namespace
  {
    /**
     * Check the quadrilaterals of a Gmsh file (format 2, ASCII) before
     * deal.II reads it: each has four distinct nodes, and no edge is shared
     * by more than two of them. deal.II 9.4's GridIn::read_msh orders the
     * cells of a tangled mesh for minutes before it could fail (found by
     * the mesh fuzzer: fuzz/findings/); this check answers in
     * milliseconds. Files in other formats are left to GridIn.
     */
    void
    check_gmsh_connectivity(const std::string &file_name)
    {
      std::ifstream in(file_name);
      std::string   line;
      std::getline(in, line);
      if (Utilities::trim(line) != "$MeshFormat")
        return;
      double version = 0;
      in >> version;
      if (!in || version >= 3)
        return;
      // A count that the file cannot hold (each node or element takes at
      // least 8 characters) would make GridIn allocate for it: the fuzzer
      // found a node count of 4.6e10 that asked for 64 GB.
      const auto file_size = std::filesystem::file_size(file_name);
      const auto check_count = [&](const std::string &section,
                                   const std::string &count_text) {
        long long count = -1;
        std::istringstream(count_text) >> count;
        check_input(count >= 0 &&
                      static_cast<unsigned long long>(count) <= file_size / 8,
                    "The mesh file '" + file_name +
                      "' (parameter 'Mesh/Gmsh file'): its " + section +
                      " section declares " +
                      (count >= 0 ? std::to_string(count) :
                                    "'" + Utilities::trim(count_text) + "'") +
                      " entries, more than its " + std::to_string(file_size) +
                      " bytes can hold: the file is damaged.");
      };
      while (std::getline(in, line) && Utilities::trim(line) != "$Elements")
        if (Utilities::trim(line) == "$Nodes" && std::getline(in, line))
          check_count("$Nodes", line);
      std::size_t n_elements = 0;
      if (!std::getline(in, line))
        return;
      check_count("$Elements", line);
      n_elements = std::stoull(Utilities::trim(line));
      std::map<std::pair<long, long>, unsigned int> edge_count;
      const std::string where = "The mesh file '" + file_name + "' (parameter "
                                "'Mesh/Gmsh file'): element ";
      for (std::size_t e = 0; e < n_elements; ++e)
        {
          long id = 0, type = 0, n_tags = 0;
          if (!(in >> id >> type >> n_tags) || n_tags < 0 || n_tags > 100)
            return; // malformed: GridIn reports it
          long tag = 0;
          for (long t = 0; t < n_tags; ++t)
            in >> tag;
          if (type != 3)
            {
              std::getline(in, line);
              continue;
            }
          std::array<long, 4> nodes;
          for (auto &n : nodes)
            in >> n;
          if (!in)
            return;
          for (unsigned int a = 0; a < 4; ++a)
            for (unsigned int b = a + 1; b < 4; ++b)
              check_input(nodes[a] != nodes[b],
                          where + std::to_string(id) +
                            " (a quadrilateral) names node " +
                            std::to_string(nodes[a]) +
                            " twice: a degenerate cell.");
          for (unsigned int a = 0; a < 4; ++a)
            {
              const auto edge =
                std::minmax(nodes[a], nodes[(a + 1) % 4]);
              const unsigned int count = ++edge_count[edge];
              check_input(count <= 2,
                          where + std::to_string(id) + " shares its edge (" +
                            std::to_string(edge.first) + ", " +
                            std::to_string(edge.second) +
                            ") with two other quadrilaterals: the mesh is "
                            "tangled (cells overlap).");
            }
        }
    }
  } // namespace


  template <int dim>
  BackgroundGrid<dim>::BackgroundGrid(const MPI_Comm comm)
    : triangulation(comm)
    , fe(FE_Q<dim>(1), dim)
    , dof_handler(triangulation)
    , mpi_communicator(comm)
  {}


  template <int dim>
  void
  BackgroundGrid<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    {
      prm.declare_entry("Source",
                        "generator",
                        Patterns::Selection("gmsh|generator|terrain"),
                        "Where the background mesh comes from: a Gmsh file "
                        "('gmsh', see 'Gmsh file'), a deal.II GridGenerator "
                        "function ('generator', see 'Generator name'), or "
                        "terrain-following cells over a digital "
                        "elevation model ('terrain': in 3D its footprint, in "
                        "2D a section line through it; see the subsection "
                        "Terrain).");
      prm.declare_entry("Gmsh file",
                        "",
                        Patterns::FileName(),
                        "Gmsh .msh file (format 2.2 or 4.x) of quadrilaterals. "
                        "Physical tags of boundary lines become boundary ids, "
                        "physical tags of surfaces material ids. A relative "
                        "name is read relative to the first .prm file's folder.");
      prm.declare_entry(
        "Generator name",
        "subdivided_hyper_rectangle",
        Patterns::Anything(),
        "Name of a deal.II GridGenerator function, as accepted by "
        "GridGenerator::generate_from_name_and_arguments(), e.g. "
        "'subdivided_hyper_rectangle' or 'hyper_cube'.");
      prm.declare_entry(
        "Generator arguments",
        "{4, 4} : 0, 0 : 1, 1 : true",
        Patterns::Anything(),
        "Arguments of the GridGenerator function, separated by ':' (e.g. "
        "for subdivided_hyper_rectangle: repetitions : lower corner : upper "
        "corner : colorize). With colorize = true the boundary ids of a "
        "rectangle are 0 (x = x_min), 1 (x = x_max), 2 (y = y_min), 3 "
        "(y = y_max).");
      TerrainMesh::declare_parameters(prm);
      PeriodicBoundaries<dim>::declare_parameters(prm);
      prm.declare_entry("Global refinements",
                        "0",
                        Patterns::Integer(0, 12),
                        "Number of times every cell is split into 2^dim "
                        "children after the mesh is read or generated.");
      prm.declare_entry(
        "Random vertex perturbation",
        "0",
        Patterns::Double(0, 0.45),
        "Move every interior vertex by a random vector of length up to this "
        "fraction of its shortest adjacent edge (GridTools::distort_random, "
        "fixed seed, boundary vertices kept), before the global refinements: "
        "a mesh of irregular quadrilaterals from any mesh, to test that "
        "results do not depend on the cells' shape. Refining a distorted "
        "mesh keeps its distortion at every level, the usual set-up of "
        "convergence studies on quadrilaterals. 0.3 gives interior angles "
        "between roughly 40 and 140 degrees; above about 0.35 some cells "
        "become non-convex, which is an input error.");
      prm.declare_entry(
        "Scene rotation angle",
        "0",
        Patterns::Double(-360, 360),
        "Rotate the whole scene by this angle (degrees, counter-clockwise; "
        "about the z axis in 3D): the mesh and every position, vector and "
        "tensor of this file (point regions, gravity, initial velocity and "
        "stress, given boundary normals) are given in the scene's own frame "
        "and turned with it. Results in the mesh frame (positions, "
        "velocities, stresses in the output) are rotated; frame-independent "
        "ones (speeds, distances, energies) must not change.");
      prm.declare_entry(
        "Local origin",
        "auto",
        Patterns::Anything(),
        "The point o of the parameter file's frame that becomes the mesh's "
        "zero: the mesh is built at x - o, while the parameter file "
        "(regions, functions), the elevation model, release areas, hazard "
        "rasters, the point file and the statistics' centre of mass speak "
        "of x (map coordinates). The particle and mesh VTU files hold x - o "
        "(single precision cannot hold map coordinates to a cell; ParaView's "
        "Transform filter adds o back, the report states it). 'auto': the "
        "lowest corner of the coarse mesh, horizontal coordinates only, "
        "truncated towards zero to whole kilometres (zero for any mesh "
        "within 1 km of the origin, UTM coordinates keep their last three "
        "digits); or dim coordinates (m). Not together with a scene "
        "rotation.");
      prm.declare_entry(
        "Scene rotation axis",
        "0, 0, 1",
        Patterns::List(Patterns::Double(), 3, 3),
        "3D only: the axis (any length but zero) about which 'Scene rotation "
        "angle' turns the scene, counter-clockwise looking against it. In 2D "
        "the rotation is always about z.");
    }
    prm.leave_subsection();
  }


  template <int dim>
  void
  BackgroundGrid<dim>::parse_parameters(ParameterHandler  &prm,
                                        const std::string &input_directory)
  {
    prm.enter_subsection("Mesh");
    {
      source               = prm.get("Source");
      mesh_file            = resolve_path(input_directory, prm.get("Gmsh file"));
      generator_name       = prm.get("Generator name");
      generator_arguments  = prm.get("Generator arguments");
      terrain.parse_parameters(prm, input_directory);
      n_global_refinements = prm.get_integer("Global refinements");
      rotation_angle = prm.get_double("Scene rotation angle") * M_PI / 180;
      {
        const auto axis = Utilities::string_to_double(
          Utilities::split_string_list(prm.get("Scene rotation axis")));
        for (unsigned int d = 0; d < 3; ++d)
          rotation_axis[d] = axis[d];
        check_input(rotation_axis.norm() > 0,
                    "Mesh/Scene rotation axis must not be zero.");
        check_input(dim == 3 || (rotation_axis[0] == 0 &&
                                 rotation_axis[1] == 0),
                    "Mesh/Scene rotation axis: in 2D the scene turns about "
                    "z; leave the axis at 0, 0, 1.");
      }
      local_origin_setting = Utilities::trim(prm.get("Local origin"));
      if (local_origin_setting != "auto")
        {
          std::vector<double> values;
          try
            {
              values = Utilities::string_to_double(
                Utilities::split_string_list(local_origin_setting));
            }
          catch (const std::exception &)
            {
              values.clear();
            }
          check_input(values.size() == dim,
                      "Mesh/Local origin = '" + local_origin_setting +
                        "': give 'auto' or " + std::to_string(dim) +
                        " coordinates separated by commas.");
          for (unsigned int d = 0; d < dim; ++d)
            local_origin[d] = values[d];
        }
      vertex_perturbation = prm.get_double("Random vertex perturbation");
      periodic_boundaries.parse_parameters(prm);
    }
    prm.leave_subsection();
    if (source == "gmsh")
      check_input(!mesh_file.empty(),
                  "Mesh/Source = gmsh, but 'Mesh/Gmsh file' is empty.");
    check_input(dim == 2 || terrain.section_length() == 0,
                "Mesh/Terrain/Section line is for 2D meshes (a section "
                "through the elevation model); a 3D terrain mesh covers the "
                "model's footprint, cropped by 'Area of interest'.");
    if (source == "terrain" && dim == 2)
      check_input(terrain.section_length() > 0,
                  "Mesh/Source = terrain in 2D meshes a section through the "
                  "elevation model: set 'Mesh/Terrain/Section line = x0, "
                  "y0 : x1, y1' (two different points, map coordinates).");
  }


  template <int dim>
  void
  BackgroundGrid<dim>::create()
  {
    if (source == "gmsh")
      {
        check_input(static_cast<bool>(std::ifstream(mesh_file)),
                    "Cannot open the mesh file '" + mesh_file +
                      "' (parameter 'Mesh/Gmsh file').");
        check_gmsh_connectivity(mesh_file);
        GridIn<dim> grid_in;
        grid_in.attach_triangulation(triangulation);
        try
          {
            std::ifstream in(mesh_file);
            grid_in.read_msh(in);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream s;
            e.print_info(s);
            throw InputError("Cannot read the mesh file '" + mesh_file +
                             "': " + Utilities::trim(s.str()));
          }
      }
    else if (source == "terrain")
      terrain.create(triangulation);
    else if (generator_name == "subdivided_hyper_rectangle")
      create_subdivided_hyper_rectangle();
    else
      {
        try
          {
            GridGenerator::generate_from_name_and_arguments(
              triangulation, generator_name, generator_arguments);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream s;
            e.print_info(s);
            throw InputError("Mesh/Generator name = '" + generator_name +
                             "' with Mesh/Generator arguments = '" +
                             generator_arguments +
                             "' failed: " + Utilities::trim(s.str()));
          }
      }
    // Perturb the coarse mesh, then refine: each refinement halves h and
    // keeps the cells' shapes (a sequence of meshes for a convergence
    // study). Perturbing after refinement would distort every level anew,
    // and points then sit close to the edges of thin cells and cross them.
    if (vertex_perturbation > 0)
      GridTools::distort_random(vertex_perturbation, triangulation, true);
    // On the coarse mesh (p4est's connectivity) and in the parameter
    // file's frame (the planes of the pairs), before the rotation.
    periodic_boundaries.apply_to_coarse_mesh(triangulation);
    triangulation.refine_global(n_global_refinements);

    check_cell_geometry();

    if (local_origin_setting == "auto")
      {
        local_origin = Tensor<1, dim>();
        const auto box = GridTools::compute_bounding_box(triangulation);
        for (unsigned int d = 0; d + 1 < dim; ++d)
          local_origin[d] =
            std::trunc(Utilities::MPI::min(box.get_boundary_points().first[d],
                                           mpi_communicator) /
                       1000.) *
            1000.;
      }
    has_local_origin = local_origin.norm() > 0;
    check_input(!has_local_origin || rotation_angle == 0,
                "Mesh/Local origin: the scene is both shifted (origin " +
                  Utilities::to_string(local_origin[0]) +
                  ", ...) and rotated (Mesh/Scene rotation angle); use one of "
                  "them (set 'Local origin = " +
                  std::string(dim == 2 ? "0, 0" : "0, 0, 0") +
                  "' to keep map coordinates).");

    rotation = unit_symmetric_tensor<dim>();
    if (has_local_origin)
      GridTools::transform([this](const Point<dim> &x) {
        return to_mesh_frame(x);
      },
                           triangulation);
    if (rotation_angle != 0)
      {
        if constexpr (dim == 3)
          rotation = Physics::Transformations::Rotations::rotation_matrix_3d(
            rotation_axis / rotation_axis.norm(), rotation_angle);
        else
          {
            // About z, counter-clockwise seen from +z (an axis 0, 0, -1
            // turns the other way).
            const double angle =
              rotation_axis[2] > 0 ? rotation_angle : -rotation_angle;
            rotation[0][0] = rotation[1][1] = std::cos(angle);
            rotation[1][0]                  = std::sin(angle);
            rotation[0][1]                  = -std::sin(angle);
          }
        GridTools::transform([this](const Point<dim> &x) {
          return to_mesh_frame(x);
        },
                             triangulation);
        periodic_boundaries.set_rotation(rotation);
      }

    setup_partition_data();
  }


  template <int dim>
  void
  BackgroundGrid<dim>::check_cell_geometry() const
  {
    // Smallest sine of a vertex angle (2D; the scaled Jacobian in 3D)
    // accepted: below it the cell is degenerate to round-off.
    constexpr double min_scaled_jacobian = 1e-10;
    std::string      message;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int v : cell->vertex_indices())
          {
            // Jacobian of the multilinear map at vertex v: column d is the
            // edge to the neighbour along reference direction d (deal.II
            // numbers vertices lexicographically).
            Tensor<2, dim> jacobian;
            double         edge_lengths = 1;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const unsigned int w    = v ^ (1u << d);
                const double       sign = (v & (1u << d)) ? -1. : 1.;
                const Tensor<1, dim> edge =
                  sign * (cell->vertex(w) - cell->vertex(v));
                for (unsigned int a = 0; a < dim; ++a)
                  jacobian[a][d] = edge[a];
                edge_lengths *= edge.norm();
              }
            const double scaled =
              edge_lengths > 0 ? determinant(jacobian) / edge_lengths : 0;
            if (scaled > min_scaled_jacobian)
              continue;
            std::ostringstream s;
            s << "The background mesh ("
              << (source == "gmsh" ? "file '" + mesh_file + "'" :
                                     "generator '" + generator_name + "'")
              << ") has a cell whose isoparametric map cannot be inverted: "
              << "the cell with vertices";
            // In 2D, counter-clockwise (deal.II numbers them
            // lexicographically).
            for (unsigned int i = 0; i < cell->n_vertices(); ++i)
              {
                const unsigned int u = (dim == 2 && i >= 2) ? 5 - i : i;
                s << (i == 0 ? " (" : ", (") << cell->vertex(u) << ')';
              }
            s << " has a Jacobian determinant of " << determinant(jacobian)
              << " at vertex (" << cell->vertex(v) << ") ("
              << (scaled < -min_scaled_jacobian ? "negative" : "zero")
              << ": the cell is "
              << (dim == 2 ? "non-convex, self-intersecting or of zero area" :
                             "inverted or degenerate")
              << "). Material points could not be located in it. Move the "
                 "vertex so that every cell is convex (in Gmsh, e.g. "
                 "Mesh.Optimize = 1, or look at the cell near this vertex)"
              << (vertex_perturbation > 0 ?
                    ", or lower 'Mesh/Random vertex perturbation'" :
                    "")
              << '.';
            message = s.str();
            break;
          }
        if (!message.empty())
          break;
      }
    for (const auto &m :
         Utilities::MPI::all_gather(mpi_communicator, message))
      check_input(m.empty(), m);
  }


  template <int dim>
  void
  BackgroundGrid<dim>::create_subdivided_hyper_rectangle()
  {
    // deal.II's string interface picks the overload with step sizes; the
    // one with repetitions is what users want, so parse it here.
    const std::string parameter = "Mesh/Generator arguments = '" +
                                  generator_arguments + "'";
    const auto parts = Utilities::split_string_list(generator_arguments, ':');
    check_input(parts.size() == 3 || parts.size() == 4,
                parameter + ": expected 'repetitions : lower corner : upper "
                            "corner [: colorize]', e.g. '{4, 2} : 0, 0 : 2, 1 : "
                            "true'.");
    auto numbers = [&](std::string text) {
      text.erase(std::remove(text.begin(), text.end(), '{'), text.end());
      text.erase(std::remove(text.begin(), text.end(), '}'), text.end());
      const auto entries = Utilities::split_string_list(text, ',');
      check_input(entries.size() == dim,
                  parameter + ": '" + text + "' must have " +
                    std::to_string(dim) + " entries.");
      std::vector<double> values;
      for (const auto &e : entries)
        values.push_back(parse_number(e, parameter + ": "));
      return values;
    };
    const auto         n  = numbers(parts[0]);
    const auto         lo = numbers(parts[1]);
    const auto         hi = numbers(parts[2]);
    std::vector<unsigned int> repetitions;
    Point<dim>         p0, p1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        check_input(n[d] >= 1 && n[d] == std::floor(n[d]) && lo[d] < hi[d],
                    parameter + ": repetitions must be whole numbers >= 1 "
                                "and the lower corner below the upper one.");
        repetitions.push_back(static_cast<unsigned int>(n[d]));
        p0[d] = lo[d];
        p1[d] = hi[d];
      }
    const bool colorize =
      parts.size() == 4 && Utilities::trim(parts[3]) == "true";
    GridGenerator::subdivided_hyper_rectangle(
      triangulation, repetitions, p0, p1, colorize);
  }


  namespace
  {
    /// The scene rotation as a 3x3 matrix (about z in 2D), for stresses.
    template <int dim>
    Tensor<2, 3>
    rotation_3d(const Tensor<2, dim> &rotation)
    {
      Tensor<2, 3> R = unit_symmetric_tensor<3>();
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          R[a][b] = rotation[a][b];
      return R;
    }
  } // namespace


  template <int dim>
  SymmetricTensor<2, 3>
  BackgroundGrid<dim>::to_mesh_frame(const SymmetricTensor<2, 3> &t) const
  {
    const Tensor<2, 3> R = rotation_3d<dim>(rotation);
    return symmetrize(R * Tensor<2, 3>(t) * transpose(R));
  }


  template <int dim>
  SymmetricTensor<2, 3>
  BackgroundGrid<dim>::to_scene_frame(const SymmetricTensor<2, 3> &t) const
  {
    const Tensor<2, 3> R = rotation_3d<dim>(rotation);
    return symmetrize(transpose(R) * Tensor<2, 3>(t) * R);
  }


  template <int dim>
  void
  BackgroundGrid<dim>::setup_partition_data()
  {
    double h = std::numeric_limits<double>::max();
    cell_sizes.assign(triangulation.n_active_cells(), 0.);
    vertices_of_cells.assign(triangulation.n_active_cells(), {});
    for (const auto &cell : triangulation.active_cell_iterators())
      if (!cell->is_artificial())
        {
          for (const unsigned int v : cell->vertex_indices())
            vertices_of_cells[cell->active_cell_index()][v] = cell->vertex(v);
          cell_sizes[cell->active_cell_index()] =
            cell->minimum_vertex_distance();
          if (cell->is_locally_owned())
            h = std::min(h, cell_sizes[cell->active_cell_index()]);
        }
    min_cell_size = Utilities::MPI::min(h, mpi_communicator);
    if constexpr (dim == 2)
      {
        bilinear_maps.assign(triangulation.n_active_cells(), {});
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            bilinear_maps[cell->active_cell_index()] =
              BilinearCellMap(vertices_of_cells[cell->active_cell_index()]);
      }
    else
      {
        parallelepiped_maps.assign(triangulation.n_active_cells(), {});
        extruded_map_index.assign(triangulation.n_active_cells(),
                                  numbers::invalid_unsigned_int);
        extruded_maps.clear();
        for (const auto &cell : triangulation.active_cell_iterators())
          if (!cell->is_artificial())
            {
              const auto &vertices = vertices_of_cells[cell->active_cell_index()];
              parallelepiped_maps[cell->active_cell_index()] =
                ParallelepipedMap(vertices);
              const ExtrudedCellMap extruded(vertices);
              if (extruded.is_extruded())
                {
                  extruded_map_index[cell->active_cell_index()] =
                    extruded_maps.size();
                  extruded_maps.push_back(extruded);
                }
            }
      }

    dof_handler.distribute_dofs(fe);
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);
  }


  template class BackgroundGrid<2>;
  template class BackgroundGrid<3>;
} // namespace MPM
