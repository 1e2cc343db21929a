#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>

#include <deal.II/lac/vector.h>

#include <mpm/base/function_input.h>
#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/material_points/point_generator.h>
#include <mpm/material_points/property_layout.h>

#include <fstream>
#include <limits>
#include <sstream>

namespace MPM
{
  template <int dim>
  bool
  PointGenerator<dim>::Region::contains(const Point<dim> &p,
                                        const double      h) const
  {
    if (type == "function")
      {
        inside->set_time(h);
        return inside->value(p) > 0;
      }
    if (type == "box")
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (p[d] < box_lower[d] || p[d] > box_upper[d])
            return false;
        return true;
      }
    if (type == "polygon")
      return release_area.contains(p, h);
    return true;
  }


  template <int dim>
  void
  PointGenerator<dim>::declare_name_list(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    prm.declare_entry("List of regions",
                      "region",
                      Patterns::Anything(),
                      "Comma separated names of the regions filled with "
                      "material points; each has a subsection of its own.");
    prm.leave_subsection();
  }


  template <int dim>
  std::vector<std::string>
  PointGenerator<dim>::read_name_list(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    const auto names = split_name_list(prm.get("List of regions"),
                                       "Material points/List of regions");
    prm.leave_subsection();
    return names;
  }


  template <int dim>
  void
  PointGenerator<dim>::declare_parameters(ParameterHandler               &prm,
                                          const std::vector<std::string> &names)
  {
    declare_name_list(prm);
    prm.enter_subsection("Material points");
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        prm.declare_entry(
          "Type",
          "box",
          Patterns::Selection("box|polygon|cells|function|file"),
          "How the region is given: 'box' (see 'Box'), 'polygon' (2D: the "
          "region, 3D: a release area, its footprint and depth; see "
          "'Polygon'), 'cells' (all cells whose material id is 'Cell "
          "material id'), 'function' (where 'Inside function' is positive), "
          "or 'file' (one point per line, see 'Point file').");
        prm.declare_entry(
          "Inside function",
          "1",
          Patterns::Anything(),
          "Type = function: an expression in x, y (, z) and h, the height "
          "above the ground (on a terrain mesh z - z_g(x, y); else the last "
          "coordinate), positive inside the region, e.g. a soil layer 2 m "
          "deep over a footprint: 'h < 2 && x > 10 && x < 30 ? 1 : -1'. "
          "Coordinates are in the scene's frame.");
        prm.declare_entry("Inside function constants",
                          "",
                          Patterns::Anything(),
                          "Constants of 'Inside function': 'name=value, "
                          "...'.");
        prm.declare_entry("Box",
                          dim == 2 ? "0, 0 : 1, 1" : "0, 0, 0 : 1, 1, 1",
                          Patterns::Anything(),
                          "Lower and upper corner of the box, in m, "
                          "separated by ':'.");
        ReleaseArea::declare_parameters(prm, dim);
        prm.declare_entry("Cell material id",
                          "0",
                          Patterns::Integer(0, 255),
                          "Mesh material id of the cells that are filled "
                          "(Type = cells).");
        prm.declare_entry("Point file",
                          "",
                          Patterns::FileName(),
                          "Text file with one point per line: the dim "
                          "coordinates (m) and the volume (m^3, per unit "
                          "thickness in 2D), with 'Initial stress = file' "
                          "followed by the six stress components (Pa); '#' "
                          "starts a comment. A relative name is read "
                          "relative to the first .prm file's folder.");
        prm.declare_entry(
          "Points per cell",
          "3",
          Patterns::Integer(1, 20),
          "Number of points per cell in each direction (n^dim points per "
          "cell). 3 by default, the fewest measured to give a granular "
          "flow's results within about 2 % of 4 x 4 points: in the column "
          "collapse (doc/column_collapse.md, 'mu(I) with side walls') 2 x 2 "
          "points per cell put the final height 12 % below 3 x 3 and 4 x 4 "
          "at a = 4 (those two agree within 1 %) on 5 and 2.5 mm cells "
          "alike, 15 % below 3 x 3 at a = 6, and move the deposit's thin "
          "tail by up to 14 %. 2 costs about half as much (a third in "
          "3D).");
        prm.declare_entry("Material",
                          "material",
                          Patterns::Anything(),
                          "Name of the material (from 'Materials/List of "
                          "materials') of the points of this region.");
        prm.declare_entry(
          "Initial stress",
          "none",
          Patterns::Selection("none|geostatic|function|file"),
          "'none': zero stress. 'geostatic': sigma_yy = rho g_y (y_s - y) "
          "with y_s the 'Surface elevation', sigma_xx = sigma_zz = K0 "
          "sigma_yy (y is the last coordinate). 'function': the six "
          "components xx; yy; zz; xy; yz; xz of the subsection 'Initial "
          "stress function', in Pa (yz before xz: a shear parallel to a "
          "bed normal to z is the sixth). 'file' (Type = file): the same six "
          "components follow the volume on each line of the 'Point file', "
          "as in the file that 'Output/Write point file' writes at the end "
          "of a run: a later stage starts in the stress state of an "
          "earlier one (e.g. a gravity-settled slope, or a sliding state).");
        prm.declare_entry("K0",
                          "-1",
                          Patterns::Double(),
                          "Coefficient of earth pressure at rest of the "
                          "geostatic stress; negative means the material "
                          "model's default (nu/(1-nu) for linear elasticity).");
        prm.declare_entry("Surface elevation",
                          "auto",
                          Patterns::Anything(),
                          "Elevation y_s of the free surface for the "
                          "geostatic stress in m, or 'auto' for the highest "
                          "point of the region.");
        prm.enter_subsection("Initial velocity");
        Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
        prm.leave_subsection();
        prm.enter_subsection("Initial stress function");
        Functions::ParsedFunction<dim>::declare_parameters(prm, 6);
        prm.leave_subsection();
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  template <int dim>
  void
  PointGenerator<dim>::parse_parameters(ParameterHandler      &prm,
                                        const MaterialLibrary &materials,
                                        const std::string     &input_directory)
  {
    const auto names = read_name_list(prm);
    prm.enter_subsection("Material points");
    for (const auto &name : names)
      {
        const std::string path = "Material points/" + name + "/";
        prm.enter_subsection(name);
        Region r;
        r.name = name;
        r.type = prm.get("Type");
        if (r.type == "box")
          {
            const auto corners =
              Utilities::split_string_list(prm.get("Box"), ':');
            check_input(corners.size() == 2,
                        path + "Box = '" + prm.get("Box") +
                          "': expected 'lower corner : upper corner'.");
            r.box_lower = parse_point<dim>(corners[0], path + "Box");
            r.box_upper = parse_point<dim>(corners[1], path + "Box");
            for (unsigned int d = 0; d < dim; ++d)
              check_input(r.box_lower[d] < r.box_upper[d],
                          path + "Box = '" + prm.get("Box") +
                            "': the lower corner must be below the upper "
                            "corner in every coordinate.");
          }
        else if (r.type == "polygon")
          {
          r.release_area.parse_parameters(prm, dim, path, input_directory);
          }
        else if (r.type == "cells")
          r.cell_material_id = prm.get_integer("Cell material id");
        else if (r.type == "function")
          {
            const std::string expression = prm.get("Inside function");
            const std::string where =
              path + "Inside function = '" + expression + "'";
            std::map<std::string, double> constants;
            for (const auto &c : Utilities::split_string_list(
                   prm.get("Inside function constants"), ','))
              {
                const auto parts = Utilities::split_string_list(c, '=');
                check_input(parts.size() == 2,
                            path + "Inside function constants: '" + c +
                              "' is not 'name=value'.");
                try
                  {
                    constants[parts[0]] = Utilities::string_to_double(parts[1]);
                  }
                catch (...)
                  {
                    throw InputError(path + "Inside function constants: '" +
                                     parts[1] + "' is not a number.");
                  }
              }
            // The height above the ground takes the place of the parser's
            // time variable (the last one).
            r.inside = std::make_shared<FunctionParser<dim>>(1);
            parse_function_or_throw(where, [&]() {
              r.inside->initialize(dim == 2 ? "x,y,h" : "x,y,z,h",
                                   expression,
                                   constants,
                                   true);
              r.inside->value(Point<dim>());
            });
          }
        else
          {
            r.file_name = resolve_path(input_directory, prm.get("Point file"));
            check_input(static_cast<bool>(std::ifstream(r.file_name)),
                        "Cannot open the point file '" + r.file_name +
                          "' (parameter '" + path + "Point file').");
          }
        r.points_per_cell = prm.get_integer("Points per cell");
        r.material_index =
          materials.index_of(prm.get("Material"), path + "Material");
        r.initial_stress = prm.get("Initial stress");
        check_input(r.initial_stress != "file" || r.type == "file",
                    "Material points/" + name + "/Initial stress = file "
                    "needs Type = file: the stresses are read from the "
                    "'Point file'.");
        r.k0             = prm.get_double("K0");
        const std::string surface = prm.get("Surface elevation");
        r.automatic_surface       = (surface == "auto");
        if (!r.automatic_surface)
          {
            try
              {
                r.surface_elevation = Utilities::string_to_double(surface);
              }
            catch (...)
              {
                throw InputError(path + "Surface elevation = '" + surface +
                                 "': expected a number (m) or 'auto'.");
              }
          }
        // A function is parsed, and evaluated once at the origin, here: a
        // typo in an expression or a constant is an input error naming the
        // parameter.
        const auto parse_function =
          [&](const std::string &subsection, const unsigned int n_components) {
            prm.enter_subsection(subsection);
            auto f = std::make_shared<Functions::ParsedFunction<dim>>(
              n_components);
            parse_function_or_throw(
              path + subsection + "/Function expression = '" +
                prm.get("Function expression") +
                "' (with its 'Function constants')",
              [&]() {
                f->parse_parameters(prm);
                Vector<double> values(n_components);
                f->vector_value(Point<dim>(), values);
              });
            prm.leave_subsection();
            return f;
          };
        r.initial_velocity        = parse_function("Initial velocity", dim);
        r.initial_stress_function = parse_function("Initial stress function", 6);
        prm.leave_subsection();
        regions.push_back(r);
      }
    prm.leave_subsection();
  }


  template <int dim>
  std::vector<typename PointGenerator<dim>::NewPoint>
  PointGenerator<dim>::points_of_region(const Region              &region,
                                        const BackgroundGrid<dim> &grid) const
  {
    std::vector<NewPoint> points;
    if (region.type == "file")
      {
        // Every rank reads the file and keeps the points in its own cells.
        GridTools::Cache<dim> cache(grid.triangulation, grid.mapping);
        std::ifstream         in(region.file_name);
        std::string           line;
        unsigned int          line_number = 0;
        bool                  missing     = false;
        std::string           missing_point;
        while (std::getline(in, line))
          {
            ++line_number;
            line = Utilities::trim(line.substr(0, line.find('#')));
            if (line.empty())
              continue;
            std::istringstream s(line);
            Point<dim>         p;
            double             volume = 0;
            for (unsigned int d = 0; d < dim; ++d)
              s >> p[d];
            s >> volume;
            const bool with_stress = region.initial_stress == "file";
            SymmetricTensor<2, 3> stress;
            if (with_stress)
              for (unsigned int k = 0; k < 6; ++k)
                s >> stress[voigt_index[k][0]][voigt_index[k][1]];
            check_input(!s.fail() && volume > 0,
                        region.file_name + ", line " +
                          std::to_string(line_number) + ": expected " +
                          std::to_string(dim) +
                          " coordinates and a positive volume" +
                          (with_stress ? ", then the six stress components "
                                         "xx yy zz xy yz xz (Initial stress "
                                         "= file)." :
                                         "."));
            // Positions in the file are in the scene's frame.
            p                = grid.to_mesh_frame(p);
            const auto found = GridTools::find_active_cell_around_point(
              cache, p, typename Triangulation<dim>::active_cell_iterator(), {}, 1e-10);
            if (found.first.state() != IteratorState::valid)
              {
                missing = true;
                missing_point =
                  region.file_name + ", line " + std::to_string(line_number);
                break;
              }
            if (found.first->is_locally_owned())
              points.push_back({p, found.second, found.first, volume, stress});
          }
        check_input(!missing,
                    "Material point at " + missing_point +
                      " lies outside the mesh.");
        return points;
      }

    const QIterated<dim> sub_cell_centres(QMidpoint<1>(),
                                          region.points_per_cell);
    FEValues<dim> fe_values(grid.mapping,
                            grid.fe,
                            sub_cell_centres,
                            update_quadrature_points | update_JxW_values);

    // Cells outside this box are skipped (a function region has none).
    BoundingBox<dim> region_box;
    const bool has_box = region.type == "box" || region.type == "polygon";
    if (region.type == "box")
      region_box = BoundingBox<dim>({region.box_lower, region.box_upper});
    else if (region.type == "polygon")
      {
        // In 3D the footprint's prism, any height.
        const auto bounds = region.release_area.footprint_bounds();
        Point<dim> lo, hi;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = d < 2 ? bounds[d] : -std::numeric_limits<double>::max();
            hi[d] = d < 2 ? bounds[2 + d] : std::numeric_limits<double>::max();
          }
        region_box = BoundingBox<dim>({lo, hi});
      }

    for (const auto &cell : grid.triangulation.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        if (region.type == "cells")
          {
            if (cell->material_id() != region.cell_material_id)
              continue;
          }
        else
          {
            // Regions are given in the scene's frame.
            BoundingBox<dim> cell_box = cell->bounding_box();
            if (grid.is_rotated() || grid.get_local_origin().norm() > 0)
              {
                std::vector<Point<dim>> vertices;
                for (const unsigned int v : cell->vertex_indices())
                  vertices.push_back(grid.to_scene_frame(cell->vertex(v)));
                cell_box = BoundingBox<dim>(vertices);
              }
            if (has_box && region_box.get_neighbor_type(cell_box) ==
                             NeighborType::not_neighbors)
              continue;
          }

        fe_values.reinit(cell);
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const Point<dim> &x = fe_values.quadrature_point(q);
            if (region.contains(grid.to_scene_frame(x),
                                grid.height_above_ground(x)))
              points.push_back({x,
                                sub_cell_centres.point(q),
                                cell,
                                fe_values.JxW(q),
                                SymmetricTensor<2, 3>()});
          }
      }
    return points;
  }


  template <int dim>
  std::vector<typename PointGenerator<dim>::RegionBeyondMesh>
  PointGenerator<dim>::regions_beyond_mesh(
    const BackgroundGrid<dim>            &grid,
    const std::set<types::boundary_id> &constrained_ids) const
  {
    const MPI_Comm comm = grid.triangulation.get_communicator();
    FEFaceValues<dim> face_values(grid.mapping,
                                  grid.fe,
                                  QMidpoint<dim - 1>(),
                                  update_quadrature_points |
                                    update_normal_vectors | update_JxW_values);
    std::vector<RegionBeyondMesh> beyond;
    for (const auto &region : regions)
      {
        if (region.type != "box" && region.type != "polygon" &&
            region.type != "function")
          continue;
        double crossed = 0;
        for (const auto &cell : grid.triangulation.active_cell_iterators())
          if (cell->is_locally_owned() && cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  constrained_ids.count(cell->face(f)->boundary_id()) == 0)
                {
                  face_values.reinit(cell, f);
                  // Just outside the face: a millionth of the cell's size.
                  const Point<dim> x =
                    face_values.quadrature_point(0) +
                    1e-6 * cell->diameter() * face_values.normal_vector(0);
                  if (region.contains(grid.to_scene_frame(x),
                                      grid.height_above_ground(x)))
                    crossed += face_values.JxW(0);
                }
        crossed = Utilities::MPI::sum(crossed, comm);
        if (crossed == 0)
          continue;
        RegionBeyondMesh r;
        r.name         = region.name;
        r.crossed_area = crossed;
        double region_volume = -1;
        if (region.type == "box")
          {
            region_volume = 1;
            for (unsigned int d = 0; d < dim; ++d)
              region_volume *= region.box_upper[d] - region.box_lower[d];
          }
        else if (region.type == "polygon" && dim == 2)
          region_volume = region.release_area.footprint_area();
        if (region_volume >= 0)
          {
            double created = 0;
            for (const auto &p : points_of_region(region, grid))
              created += p.volume;
            r.volume_lost =
              std::max(0., region_volume - Utilities::MPI::sum(created, comm));
          }
        beyond.push_back(r);
      }
    return beyond;
  }


  template <int dim>
  std::vector<typename PointGenerator<dim>::RegionSummary>
  PointGenerator<dim>::generate(
    const BackgroundGrid<dim>       &grid,
    const MaterialLibrary           &materials,
    const Tensor<1, dim>            &gravity,
    Particles::ParticleHandler<dim> &particle_handler,
    const unsigned int               velocity_gradient_slot,
    const InitialPoreWater<dim>     &pore_water) const
  {
    using Layout              = PropertyLayout<dim>;
    const MPI_Comm comm       = grid.triangulation.get_communicator();
    const unsigned n_props    = particle_handler.n_properties_per_particle();
    types::particle_index next_id = 0;
    std::vector<RegionSummary> summaries;

    for (const auto &region : regions)
      {
        RegionSummary summary;
        summary.name = region.name;
        const auto points = points_of_region(region, grid);
        // Ids of this rank's points start after those of lower ranks.
        unsigned long long n_local = points.size(), first_id = 0;
        MPI_Exscan(&n_local, &first_id, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          first_id = 0;
        const unsigned long long n_total = Utilities::MPI::sum(n_local, comm);
        check_input(n_total > 0,
                    "Material points/" + region.name +
                      " holds no material point: the region lies outside "
                      "the mesh or is smaller than a sub-cell.");

        double surface = region.surface_elevation;
        if (region.automatic_surface)
          {
            double y_max = -std::numeric_limits<double>::max();
            for (const auto &p : points)
              y_max =
                std::max(y_max, grid.to_scene_frame(p.location)[dim - 1]);
            surface = Utilities::MPI::max(y_max, comm);
          }

        const Material &material = materials[region.material_index];
        const double    k0 =
          region.k0 >= 0 ? region.k0 : material.model->default_k0();

        std::vector<double> properties(n_props, 0.);
        types::particle_index id = next_id + first_id;
        for (const auto &p : points)
          {
            std::fill(properties.begin(), properties.end(), 0.);
            properties[Layout::mass]   = material.density * p.volume;
            properties[Layout::volume] = p.volume;
            summary.volume += p.volume;
            summary.mass += properties[Layout::mass];
            // The functions of the parameter file live in the scene's
            // frame; their values are turned into the mesh's.
            const Point<dim> X = grid.to_scene_frame(p.location);
            Tensor<1, dim>   velocity;
            for (unsigned int d = 0; d < dim; ++d)
              velocity[d] = region.initial_velocity->value(X, d);
            velocity = grid.to_mesh_frame(velocity);
            for (unsigned int d = 0; d < dim; ++d)
              properties[Layout::velocity + d] = velocity[d];
            if (velocity_gradient_slot != numbers::invalid_unsigned_int)
              {
                // The parsed function's gradient is a difference quotient
                // (AutoDerivativeFunction): exact for linear fields.
                Tensor<2, dim> G;
                for (unsigned int d = 0; d < dim; ++d)
                  G[d] = region.initial_velocity->gradient(X, d);
                G = grid.to_mesh_frame(G);
                for (unsigned int a = 0; a < dim; ++a)
                  for (unsigned int b = 0; b < dim; ++b)
                    properties[velocity_gradient_slot + a * dim + b] = G[a][b];
              }

            SymmetricTensor<2, 3> stress;
            if (region.initial_stress == "geostatic")
              {
                // A saturated material's effective stress: the mixture's
                // weight less the pore pressure.
                const bool   saturated = material.porosity > 0 &&
                                       pore_water.pressure != nullptr;
                // Submerged: less the still water's buoyancy, whose
                // hydrostatic pressure the pore pressure does not hold.
                const double rho =
                  material.density +
                  (saturated ? material.porosity * pore_water.density : 0.) -
                  (saturated ? pore_water.ambient_density : 0.);
                double s_v = rho * gravity[dim - 1] * (surface - X[dim - 1]);
                if (saturated)
                  s_v += pore_water.pressure(X);
                for (unsigned int d = 0; d < 3; ++d)
                  stress[d][d] = (d == dim - 1) ? s_v : k0 * s_v;
              }
            else if (region.initial_stress == "function")
              for (unsigned int k = 0; k < 6; ++k)
                stress[voigt_index[k][0]][voigt_index[k][1]] =
                  region.initial_stress_function->value(X, k);
            else if (region.initial_stress == "file")
              stress = p.stress;
            write_symmetric_tensor(grid.to_mesh_frame(stress),
                                   &properties[Layout::stress]);

            properties[Layout::material_id] = region.material_index;
            material.model->initialize_state(
              ArrayView<double>(properties.data() + Layout::state,
                                n_props - Layout::state));

            particle_handler.insert_particle(p.location,
                                             p.reference_location,
                                             id++,
                                             p.cell,
                                             ArrayView<const double>(
                                               properties));
          }
        next_id += n_total;
        summary.n_points = n_total;
        summary.volume   = Utilities::MPI::sum(summary.volume, comm);
        summary.mass     = Utilities::MPI::sum(summary.mass, comm);
        summaries.push_back(summary);
      }
    particle_handler.update_cached_numbers();
    return summaries;
  }


  template class PointGenerator<2>;
  template class PointGenerator<3>;
} // namespace MPM
