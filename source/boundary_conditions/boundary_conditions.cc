#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/boundary_conditions/node_frames.h>
#include <mpm/boundary_conditions/wall_friction.h>

#include <mpm/boundary_conditions/boundary_face_areas.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

namespace MPM
{
  template <int dim>
  void
  BoundaryConditions<dim>::declare_name_list(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry("List of boundaries",
                      "",
                      Patterns::Anything(),
                      "Comma separated names of the constrained boundaries; "
                      "each has a subsection of its own. Boundary ids that "
                      "no boundary names are free.");
    prm.leave_subsection();
  }


  template <int dim>
  std::vector<std::string>
  BoundaryConditions<dim>::read_name_list(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    const auto names =
      split_name_list(prm.get("List of boundaries"),
                      "Boundary conditions/List of boundaries");
    prm.leave_subsection();
    for (const auto &name : names)
      check_input(name != "Side walls",
                  "'Boundary conditions/List of boundaries' names a boundary "
                  "'Side walls': that subsection is the side-wall friction's "
                  "(SideWallFriction); give the boundary another name.");
    return names;
  }


  template <int dim>
  void
  BoundaryConditions<dim>::declare_parameters(
    ParameterHandler               &prm,
    const std::vector<std::string> &names)
  {
    declare_name_list(prm);
    WallGap<dim>::declare_parameters(prm);
    prm.enter_subsection("Boundary conditions");
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        prm.declare_entry("Boundary ids",
                          "0",
                          Patterns::List(Patterns::Integer(0, 254)),
                          "Mesh boundary ids (Gmsh physical tags) this "
                          "boundary covers.");
        prm.declare_entry("Type",
                          "fixed",
                          Patterns::Selection(
                            "free|fixed|slip|friction|velocity|traction|"
                            "absorbing"),
                          "free; fixed (zero velocity); slip (zero normal "
                          "velocity); friction (zero normal velocity and "
                          "the 'Basal law'); velocity (prescribed normal and "
                          "tangential velocity, 2D); traction (free, loaded "
                          "by the 'Traction'); absorbing (free, with "
                          "dashpots that absorb the waves arriving at the "
                          "boundary, 'Absorbing density' and the wave "
                          "speeds, and loaded by the 'Traction': the mesh "
                          "ends where the ground does not; "
                          "doc/boundary_conditions.md).");
        prm.declare_entry("Friction coefficient",
                          "0",
                          Patterns::Double(0),
                          "Coulomb friction coefficient mu >= 0 of the basal "
                          "law (Type = friction): the rate-independent part "
                          "mu sigma_n of every law.");
        prm.declare_entry("Basal law",
                          "coulomb",
                          Patterns::Selection(
                            BasalLawRegistry<dim>::names()),
                          "The tangential resistance of a Type = friction "
                          "boundary (doc/boundary_conditions.md). " +
                            BasalLawRegistry<dim>::descriptions());
        BasalLawRegistry<dim>::declare_parameters(prm);
        NormalStressMemory::declare_parameters(prm);
        prm.declare_entry("Normal",
                          "mesh",
                          Patterns::Selection("mesh|given"),
                          "Outward normal of the node frames: 'mesh' averages "
                          "the outward normals of the node's boundary faces "
                          "(weighted by face size); 'given' uses 'Outward "
                          "normal' at every node of the boundary.");
        prm.declare_entry("Outward normal",
                          dim == 2 ? "0, -1" : "0, 0, -1",
                          Patterns::Anything(),
                          "Outward normal vector (need not be normalised) "
                          "for Normal = given.");
        prm.declare_entry("Velocity",
                          "0, 0",
                          Patterns::Anything(),
                          "Prescribed velocity (m/s) for Type = velocity, as "
                          "(normal, tangential) components in the node frame; "
                          "the tangent is the outward normal turned by +90 "
                          "degrees.");
        prm.declare_entry("Drainage",
                          "impermeable",
                          Patterns::Selection("impermeable|drained"),
                          "For the pore water of saturated materials "
                          "(doc/pore_water.md), a wall (fixed, slip, "
                          "friction, velocity) is impermeable (the water's "
                          "normal velocity is held as the skeleton's; its "
                          "tangential one is free, also on a fixed wall) or "
                          "drained (the water passes: its velocity is free "
                          "there and the pore pressure on the wall zero, "
                          "as on a filter). Free and traction boundaries "
                          "always drain.");
        prm.declare_entry("Traction",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Patterns::Anything(),
                          "Force per area in Pa on the boundary's faces for "
                          "Type = traction or absorbing, as components in "
                          "the scene's frame (x, y[, z]); e.g. '0, -1e5' "
                          "presses a top face down with 100 kPa. It acts on "
                          "the nodes of the faces that hold material. On an "
                          "absorbing boundary under gravity it is the "
                          "static reaction of the ground beyond the mesh "
                          "(without it the body sinks through the "
                          "dashpots).");
        prm.declare_entry("Absorbing density",
                          "0",
                          Patterns::Double(0),
                          "Type = absorbing: the density (kg/m^3) of the "
                          "ground beyond the boundary. With the wave speeds "
                          "below it gives the dashpots' tractions "
                          "-rho c_p v_n (normal) and -rho c_s v_t "
                          "(tangential), which absorb plane waves meeting "
                          "the boundary head-on (Lysmer and Kuhlemeyer "
                          "1969). For an elastic ground c_p = sqrt((lambda "
                          "+ 2 G) / rho), c_s = sqrt(G / rho).");
        prm.declare_entry("Absorbing P-wave speed",
                          "0",
                          Patterns::Double(0),
                          "Type = absorbing: c_p (m/s), the speed of the "
                          "compression waves beyond the boundary.");
        prm.declare_entry("Absorbing S-wave speed",
                          "0",
                          Patterns::Double(0),
                          "Type = absorbing: c_s (m/s), the speed of the "
                          "shear waves beyond the boundary (0 for a "
                          "liquid); at most the P-wave speed.");
        prm.declare_entry("Absorbing input velocity",
                          "none",
                          Patterns::Anything(),
                          "Type = absorbing: 'none', or the velocity (m/s) "
                          "that a wave coming in through the boundary gives "
                          "the ground there, a function of the time t with "
                          "one component per direction of the scene's "
                          "frame, e.g. '0.1 * sin(2 * pi * 2 * t) * (t < "
                          "1); 0' (an earthquake's horizontal motion "
                          "entering through the base). The dashpots then "
                          "act on 2 v_in - v: the wave enters, what the "
                          "mesh sends back leaves (a compliant base; on a "
                          "free surface above an elastic column the motion "
                          "is 2 v_in).");
        prm.declare_entry("Pore pressure",
                          "none",
                          Patterns::Anything(),
                          "For the pore water: 'none', or the pressure in "
                          "Pa (compression positive) of the water this "
                          "boundary drains into, a function of the scene's "
                          "x, y (, z) and the time t, e.g. '9810 * (5 - y)' "
                          "for a reservoir whose level is at y = 5 m. Its "
                          "faces push the water with n p dA and the "
                          "skeleton with (1 - n) p dA (n the nodal "
                          "porosity), the total p dA of water standing on "
                          "the boundary, at the nodes that hold saturated "
                          "material. A wall with a pore pressure must be "
                          "'Drainage = drained'; on Type = friction the basal "
                          "law takes the effective normal stress, the "
                          "wall's push less p.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  template <int dim>
  void
  BoundaryConditions<dim>::parse_parameters(ParameterHandler &prm)
  {
    const auto names = read_name_list(prm);
    wall_gap.parse_parameters(prm);
    prm.enter_subsection("Boundary conditions");
    for (const auto &name : names)
      {
        const std::string path = "Boundary conditions/" + name + "/";
        prm.enter_subsection(name);
        BoundarySpec<dim> s;
        s.name = name;
        for (const int id : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Boundary ids"))))
          s.ids.push_back(id);
        s.type =
          select_choice<BoundaryType>(prm.get("Type"),
                                      {{"free", BoundaryType::free},
                                       {"fixed", BoundaryType::fixed},
                                       {"slip", BoundaryType::slip},
                                       {"friction", BoundaryType::friction},
                                       {"velocity", BoundaryType::velocity},
                                       {"traction", BoundaryType::traction},
                                       {"absorbing", BoundaryType::absorbing}},
                                      path + "Type");
        if (s.type == BoundaryType::friction)
          {
            try
              {
                auto law =
                  BasalLawRegistry<dim>::create(prm.get("Basal law"),
                                                "Basal law",
                                                prm,
                                                prm.get_double(
                                                  "Friction coefficient"));
                NormalStressMemory memory;
                memory.parse_parameters(prm);
                law->set_normal_stress_memory(memory);
                s.law = std::move(law);
              }
            catch (const InputError &e)
              {
                throw InputError(path + e.what());
              }
          }
        s.normal_from_mesh     = prm.get("Normal") == "mesh";
        if (!s.normal_from_mesh)
          {
            s.given_normal =
              parse_point<dim>(prm.get("Outward normal"), path + "Outward normal");
            check_input(s.given_normal.norm() > 0,
                        path + "Outward normal must not be zero.");
            s.given_normal /= s.given_normal.norm();
          }
        if (s.type == BoundaryType::velocity)
          {
            check_input(dim == 2,
                        path + "Type = velocity is implemented in 2D only.");
            s.local_velocity = parse_point<dim>(prm.get("Velocity"),
                                                 path + "Velocity");
          }
        s.drained = prm.get("Drainage") == "drained";
        if (prm.get("Pore pressure") != "none")
          {
            s.pore_pressure = prm.get("Pore pressure");
            check_input(!is_wall(s.type) || s.drained,
                        path + "Pore pressure needs 'Drainage = drained' "
                               "on a wall: the water of a prescribed "
                               "pressure passes through the boundary.");
          }
        if (carries_traction(s.type))
          s.traction =
            parse_point<dim>(prm.get("Traction"), path + "Traction");
        if (s.type == BoundaryType::absorbing)
          {
            const double rho = prm.get_double("Absorbing density");
            const double c_p = prm.get_double("Absorbing P-wave speed");
            const double c_s = prm.get_double("Absorbing S-wave speed");
            check_input(rho > 0 && c_p > 0,
                        path +
                          "Type = absorbing needs 'Absorbing density' "
                          "and 'Absorbing P-wave speed' > 0 (the "
                          "ground beyond the boundary); they are " +
                          std::to_string(rho) + " kg/m^3 and " +
                          std::to_string(c_p) + " m/s.");
            check_input(c_s <= c_p,
                        path +
                          "Absorbing S-wave speed = " + std::to_string(c_s) +
                          " m/s is larger than the P-wave speed " +
                          std::to_string(c_p) +
                          " m/s: no elastic ground has that.");
            s.normal_impedance     = rho * c_p;
            s.tangential_impedance = rho * c_s;
            if (prm.get("Absorbing input velocity") != "none")
              s.input_velocity = prm.get("Absorbing input velocity");
          }
        else
          check_input(prm.get("Absorbing input velocity") == "none",
                      path + "Absorbing input velocity is for Type = "
                             "absorbing boundaries only.");
        prm.leave_subsection();
        specs.push_back(s);
      }
    prm.leave_subsection();
  }


  template <int dim>
  const BasalLaw<dim> *
  BoundaryConditions<dim>::basal_law(const std::string &name) const
  {
    for (const auto &s : specs)
      if (s.name == name)
        return s.law.get();
    throw InputError("There is no boundary '" + name +
                     "' in 'Boundary conditions/List of boundaries'.");
  }


  template <int dim>
  void
  BoundaryConditions<dim>::check_boundary_ids(const BackgroundGrid<dim> &grid) const
  {
    const auto mesh_ids = grid.triangulation.get_boundary_ids();
    std::string known;
    for (const auto id : mesh_ids)
      known += (known.empty() ? "" : ", ") + std::to_string(id);
    for (const auto &s : specs)
      for (const auto id : s.ids)
        check_input(std::find(mesh_ids.begin(), mesh_ids.end(), id) !=
                      mesh_ids.end(),
                    "Boundary conditions/" + s.name + "/Boundary ids names "
                      "id " + std::to_string(id) +
                      ", which the mesh does not have (its boundary ids: " +
                      known + ").");
    const auto periodic = grid.periodic_boundaries.boundary_ids();
    for (const auto &s : specs)
      for (const auto id : s.ids)
        check_input(std::find(periodic.begin(), periodic.end(), id) ==
                      periodic.end(),
                    "Boundary conditions/" + s.name + "/Boundary ids names "
                      "id " + std::to_string(id) +
                      ", which Mesh/Periodic boundaries makes periodic: a "
                      "periodic boundary takes no boundary condition.");
  }


  template <int dim>
  void
  BoundaryConditions<dim>::setup(const BackgroundGrid<dim> &grid,
                                 const NodalVector         &layout,
                                 const PeriodicNodeGroups  *periodic_nodes)
  {
    // The contact state is kept by location through a new setup (after
    // repartitioning, a node may now live on another rank).
    const WallNodeStates<dim> states_before =
      WallNodeStates<dim>::gather(grid.triangulation.get_communicator(),
                                  wall_node_states());
    const std::vector<NodeFrame<dim>> frames =
      compute_node_frames(grid, layout, specs, gravity_magnitude, periodic_nodes);
    make_wall_constraints(frames, grid.locally_relevant_dofs, normal_constraints);
    nodes = make_projections(frames, normal_constraints, layout);
    set_wall_node_states(states_before);
    wall_gap.setup(grid, specs, layout, nodes);
    tractions.setup(grid, specs, layout, periodic_nodes);
    absorbing.setup(grid, specs, layout, periodic_nodes);
    pore_pressures.setup(grid, specs, layout, periodic_nodes);
    compute_frictional_wall_area(grid, layout, periodic_nodes);
    // A periodic node's copies are one node: record_wall_tractions() keeps
    // the copy of the least global index.
    periodic_copy.assign(nodes.size(), false);
    if (periodic_nodes != nullptr)
      for (unsigned int k = 0; k < nodes.size(); ++k)
        periodic_copy[k] =
          periodic_nodes->is_later_copy(nodes[k].local_dofs[0],
                                        *layout.get_partitioner());
    // The pore water's walls: the skeleton's without the drained ones,
    // and a fixed wall holds the water's normal velocity alone. The
    // water's momentum balance has no shear stress (its force on the
    // skeleton is the drag), so no wall condition on its tangential
    // velocity: along a no-slip wall the water seeps as anywhere else.
    water_nodes.clear();
    if (with_pore_water &&
        std::any_of(specs.begin(), specs.end(), [](const auto &s) {
          return is_wall(s.type) &&
                 (s.drained || s.type == BoundaryType::fixed);
        }))
      {
        auto water_specs = specs;
        for (auto &s : water_specs)
          if (s.drained)
            s.type = BoundaryType::free;
          else if (s.type == BoundaryType::fixed)
            s.type = BoundaryType::slip;
        const auto water_frames = compute_node_frames(
          grid, layout, water_specs, gravity_magnitude, periodic_nodes);
        AffineConstraints<double> water_constraints;
        make_wall_constraints(water_frames,
                              grid.locally_relevant_dofs,
                              water_constraints);
        water_nodes =
          make_projections(water_frames, water_constraints, layout);
        separate_water_walls = true;
        std::map<unsigned int, unsigned int> water_node_at;
        for (unsigned int w = 0; w < water_nodes.size(); ++w)
          water_node_at[water_nodes[w].local_dofs[0]] = w;
        water_node_of_node.assign(nodes.size(), numbers::invalid_unsigned_int);
        for (unsigned int k = 0; k < nodes.size(); ++k)
          {
            const auto w = water_node_at.find(nodes[k].local_dofs[0]);
            if (w != water_node_at.end())
              water_node_of_node[k] = w->second;
          }
      }
    else
      separate_water_walls = false;
  }


  template <int dim>
  void
  BoundaryConditions<dim>::compute_frictional_wall_area(
    const BackgroundGrid<dim> &grid,
    const NodalVector         &layout,
    const PeriodicNodeGroups  *periodic_nodes)
  {
    wall_area.reinit(layout);
    wall_area = 0;
    if (std::none_of(specs.begin(), specs.end(), [](const auto &s) {
          return s.type == BoundaryType::friction;
        }))
      return;
    for_each_boundary_face_node_area(
      grid,
      [this](const types::boundary_id id) {
        return std::any_of(specs.begin(), specs.end(), [id](const auto &s) {
          return s.type == BoundaryType::friction &&
                 std::find(s.ids.begin(), s.ids.end(), id) != s.ids.end();
        });
      },
      [this](const auto        &cell,
             const unsigned int cell_vertex,
             const types::boundary_id,
             const double area) {
        for (unsigned int c = 0; c < dim; ++c)
          wall_area(cell->vertex_dof_index(cell_vertex, c)) += area;
      });
    wall_area.compress(VectorOperation::add);
    wall_area.update_ghost_values();
    if (periodic_nodes != nullptr)
      periodic_nodes->sum(wall_area);
  }


  template <int dim>
  void
  BoundaryConditions<dim>::drain_at_walls(
    const NodalVector &velocity_against_wall,
    NodalVector       &velocity) const
  {
    for (unsigned int k = 0; k < nodes.size(); ++k)
      {
        const auto &node = nodes[k];
        // A frictional node the last update did not hold: the wall held
        // nothing there.
        if (node.frictional && contact_state[k] == ContactState::free)
          continue;
        const unsigned int w = water_node_of_node[k];
        const Tensor<2, dim> P_w = w == numbers::invalid_unsigned_int ?
                                     unit_symmetric_tensor<dim>() :
                                     water_nodes[w].projector;
        Tensor<1, dim> v, v_wall;
        for (unsigned int c = 0; c < dim; ++c)
          {
            v[c]      = velocity.local_element(node.local_dofs[c]);
            v_wall[c] = velocity_against_wall.local_element(node.local_dofs[c]);
          }
        v += (P_w - node.projector) * (v_wall - v);
        for (unsigned int c = 0; c < dim; ++c)
          velocity.local_element(node.local_dofs[c]) = v[c];
      }
  }


  template <int dim>
  void
  BoundaryConditions<dim>::project_water_velocity(NodalVector &velocity) const
  {
    if (!separate_water_walls)
      {
        project_velocity(velocity);
        return;
      }
    // As project_velocity() by velocity (a frictional wall holds the
    // water moving into it), on the impermeable walls alone.
    for (const auto &node : water_nodes)
      {
        Tensor<1, dim> v;
        for (unsigned int c = 0; c < dim; ++c)
          v[c] = velocity.local_element(node.local_dofs[c]);
        if (node.frictional && v * node.normal <= 0)
          continue;
        v = node.projector * v + node.offset;
        for (unsigned int c = 0; c < dim; ++c)
          velocity.local_element(node.local_dofs[c]) = v[c];
      }
  }


  template <int dim>
  void
  BoundaryConditions<dim>::project_velocity(NodalVector  &velocity,
                                            const Contact contact) const
  {
    for (unsigned int k = 0; k < nodes.size(); ++k)
      {
        const auto    &node = nodes[k];
        Tensor<1, dim> v;
        for (unsigned int c = 0; c < dim; ++c)
          v[c] = velocity.local_element(node.local_dofs[c]);
        // The material has left the wall around the node: free both ways.
        if (node.frictional && !wall_gap.touches(k))
          continue;
        const ContactState last = contact == Contact::as_last_update ?
                                    contact_state[k] :
                                    ContactState::free;
        // A frictional wall only pushes: a node moving away from it is
        // free, unless the last nodal update held it.
        if (node.frictional && v * node.normal <= 0 &&
            last == ContactState::free)
          continue;
        // A node that stuck did not move at all.
        if (last == ContactState::stuck)
          v = Tensor<1, dim>();
        v = node.projector * v + node.offset;
        for (unsigned int c = 0; c < dim; ++c)
          velocity.local_element(node.local_dofs[c]) = v[c];
      }
  }


  template <int dim>
  void
  BoundaryConditions<dim>::constrain_updated_velocity(NodalVector &velocity)
  {
    // Edge nodes are held bilaterally: apply_friction() set their state.
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (nodes[k].frictional)
        {
          Tensor<1, dim> v;
          for (unsigned int c = 0; c < dim; ++c)
            v[c] = velocity.local_element(nodes[k].local_dofs[c]);
          // apply_friction() has marked the nodes that stick.
          if (v * nodes[k].normal <= 0 || !wall_gap.touches(k))
            contact_state[k] = ContactState::free;
          else if (contact_state[k] != ContactState::stuck)
            contact_state[k] = ContactState::sliding;
        }
    project_velocity(velocity, Contact::by_velocity);
  }


  template <int dim>
  WallNodeStates<dim>
  BoundaryConditions<dim>::wall_node_states() const
  {
    WallNodeStates<dim> states;
    // set_wall_node_states() sizes both per-node vectors with the nodes.
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (contact_state[k] != ContactState::free ||
          remembered_normal_force[k] >= 0 || remembered_edge_force[k] >= 0)
        states.add(nodes[k].location,
                   contact_state[k],
                   remembered_normal_force[k],
                   remembered_edge_force[k]);
    return states;
  }


  template <int dim>
  void
  BoundaryConditions<dim>::set_wall_node_states(
    const WallNodeStates<dim> &states)
  {
    contact_state.assign(nodes.size(), ContactState::free);
    remembered_normal_force.assign(nodes.size(), -1.);
    remembered_edge_force.assign(nodes.size(), -1.);
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (nodes[k].frictional || nodes[k].edge_friction)
        {
          const auto state = states.find(nodes[k].location);
          contact_state[k] = state.contact;
          remembered_normal_force[k] = state.remembered_normal_force;
          if (nodes[k].edge_friction)
            remembered_edge_force[k] = state.remembered_edge_force;
        }
  }


  template <int dim>
  void
  BoundaryConditions<dim>::apply_friction(const NodalVector &mass,
                                          const NodalVector &velocity,
                                          NodalVector       &acceleration,
                                          const double       dt,
                                          const PoreWaterAtNodes *water)
  {
    if (recording_tractions)
      recorded_tractions.clear();
    const unsigned int n_owned =
      mass.get_partitioner()->locally_owned_size();
    for (unsigned int k = 0; k < nodes.size(); ++k)
      {
        const auto &node = nodes[k];
        if (!node.frictional && !node.edge_friction)
          continue;
        const bool held  = contact_state[k] != ContactState::free;
        contact_state[k] = ContactState::free;
        if (mass.local_element(node.local_dofs[0]) <= 0)
          continue;
        if (node.frictional && !wall_gap.touches(k))
          continue;
        Tensor<1, dim> v, a;
        for (unsigned int c = 0; c < dim; ++c)
          {
            v[c] = velocity.local_element(node.local_dofs[c]);
            a[c] = acceleration.local_element(node.local_dofs[c]);
          }
        bool         sticks = false;
        // For record_wall_tractions(): the acceleration before the wall's
        // resistance and the pore water's push p A.
        const Tensor<1, dim> a_before = a;
        double               pore_pressure_force = 0;
        // With pore water: the effective normal force is the mixture's
        // reaction, R_s + R_w, less p A. Friction takes it from the
        // skeleton's reaction R_s by the relief p A - R_w (per unit
        // skeleton mass): the drag of the nodal update has shared the
        // phases' pushes on the wall, their sum it has not. On a drained
        // wall the pressure is the boundary's own (its 'Pore pressure', 0
        // without one), whose push p A is in the phases' forces already
        // ((1 - n) p A on the skeleton, n p A on the water), and the wall
        // holds the skeleton only: the effective normal force is R_s plus
        // the part of the skeleton's push that the drag has handed to
        // the water within the step (the drag's normal force on it, which
        // PoreWater::finish_velocity() takes out again against the held
        // skeleton). Not the water's whole push after the drag: its own
        // force in it fed back into the friction and grew from round-off
        // into a normal oscillation of the layer (a sliding layer on a
        // drained bed, after 0.18 s).
        // The normal reaction per unit mass the Coulomb part takes where
        // it is not the wall's whole push.
        std::optional<double> effective_reaction;
        if (water != nullptr && node.frictional)
          {
            const NodeWater       w = node_water(node, *water);
            const Tensor<1, dim> &n = node.normal;
            const bool            drains = water_drains_along(k, n);
            const double          own =
              w.m_w * (w.v_w * n) / dt + w.F_w * n +
              water->excess_push(node.local_dofs, n);
            pore_pressure_force =
              drains     ? std::numeric_limits<double>::quiet_NaN() :
              w.n_i > 0 ? std::max(own, 0.) / w.n_i :
                          0.;
            const double relief =
              pore_water_relief(drains,
                                own,
                                w.m_w * (w.v_w_new * n) / dt,
                                w.m_w * ((w.v_w_new - w.v_w) * n) / dt -
                                  w.F_w * n,
                                w.n_i,
                                mass.local_element(node.local_dofs[0]));
            effective_reaction =
              std::max(WallFriction::normal_reaction(v, a, node.normal, dt) -
                         relief,
                       0.);
          }
        if (node.frictional && node.law->normal_stress_memory().active())
          effective_reaction = remembered_normal_reaction(
            k, v, a, mass, dt, held, effective_reaction);
        std::array<double, 2> edge_relief{{0., 0.}};
        if (water != nullptr && node.edge_friction)
          edge_relief = edge_pore_water_relief(k, *water, mass, dt);
        // Where an edge's wall has a normal-stress memory, each wall's
        // Coulomb part takes the impulse of its remembered force.
        std::array<double, 2>        edge_impulses;
        const std::array<double, 2> *remembered_edge_impulses = nullptr;
        if (node.edge_friction && edge_has_memory(node) &&
            remembered_edge_normal_impulses(
              k, v, a, mass, dt, edge_relief, edge_impulses))
          remembered_edge_impulses = &edge_impulses;
        a = node.frictional ?
              WallFriction::frictional_acceleration(v,
                                                    a,
                                                    node.normal,
                                                    *node.law,
                                                    node.geometry,
                                                    dt,
                                                    &sticks,
                                                    held,
                                                    effective_reaction) :
              WallFriction::edge_frictional_acceleration(
                v,
                a,
                node.edge_normals,
                node.edge_laws,
                node.edge_geometry,
                dt,
                &sticks,
                edge_relief,
                remembered_edge_impulses);
        if (sticks)
          contact_state[k] = ContactState::stuck;
        if (recording_tractions && node.frictional &&
            node.local_dofs[0] < n_owned && !periodic_copy[k])
          {
            const double         m = mass.local_element(node.local_dofs[0]);
            const Tensor<1, dim> &n = node.normal;
            const double reaction =
              WallFriction::normal_reaction(v, a_before, n, dt);
            WallTraction t;
            t.location   = node.location;
            t.normal     = n;
            t.area       = wall_area.local_element(node.local_dofs[0]);
            t.in_contact = reaction > 0;
            t.stuck      = sticks;
            t.effective_normal_force =
              t.in_contact ?
                m * effective_reaction.value_or(reaction) :
                0.;
            t.pore_pressure_force = pore_pressure_force;
            const Tensor<1, dim> wall_force = m * (a - a_before);
            t.tangential_force = (wall_force - (wall_force * n) * n).norm();
            const Tensor<1, dim> v_new = v + dt * a;
            t.slip_speed              = (v_new - (v_new * n) * n).norm();
            recorded_tractions.push_back(t);
          }
        for (unsigned int c = 0; c < dim; ++c)
          acceleration.local_element(node.local_dofs[c]) = a[c];
      }
  }


  template <int dim>
  std::optional<double>
  BoundaryConditions<dim>::remembered_normal_reaction(
    const unsigned int           k,
    const Tensor<1, dim>        &v,
    const Tensor<1, dim>        &a,
    const NodalVector           &mass,
    const double                 dt,
    const bool                   held,
    const std::optional<double> &effective_reaction)
  {
    const auto  &node = nodes[k];
    const double reaction =
      WallFriction::normal_reaction(v, a, node.normal, dt);
    double &N_m = remembered_normal_force[k];
    if (reaction <= 0)
      {
        // Not pushing: the wall forgets the node's normal force.
        N_m = -1;
        return effective_reaction;
      }
    // The normal force the Coulomb part would take now, against the
    // remembered N_m.
    const double m   = mass.local_element(node.local_dofs[0]);
    const double now = effective_reaction.value_or(reaction) * m;
    return node.law->normal_stress_memory().remember(
             N_m, held, now, (v - (v * node.normal) * node.normal).norm(), dt) /
           m;
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::edge_has_memory(const ConstrainedNode &node)
  {
    for (const BasalLaw<dim> *law : node.edge_laws)
      if (law != nullptr && law->normal_stress_memory().active())
        return true;
    return false;
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::remembered_edge_normal_impulses(
    const unsigned int           k,
    const Tensor<1, dim>        &v,
    const Tensor<1, dim>        &a,
    const NodalVector           &mass,
    const double                 dt,
    const std::array<double, 2> &relief,
    std::array<double, 2>       &impulses)
  {
    const auto &node   = nodes[k];
    const auto &n      = node.edge_normals;
    const auto  pushes = WallFriction::edge_wall_impulses(v, a, n, dt);
    if (!pushes)
      return false;
    const double m   = mass.local_element(node.local_dofs[0]);
    const double g01 = n[0] * n[1];
    // The slip: the speed along the edge, as remembered_normal_reaction()
    // takes the tangential speed of a node on one wall.
    const double slip = WallFriction::along_edge(v, n, 1 - g01 * g01).norm();
    for (unsigned int j = 0; j < 2; ++j)
      {
        // The impulse edge_frictional_acceleration() takes without a
        // memory.
        impulses[j]              = std::max(0., (*pushes)[j] - dt * relief[j]);
        const BasalLaw<dim> *law = node.edge_laws[j];
        if (law == nullptr || !law->normal_stress_memory().active())
          continue;
        double &N_m =
          j == 0 ? remembered_normal_force[k] : remembered_edge_force[k];
        if ((*pushes)[j] <= 0)
          {
            // Not pushing: the wall forgets the node's normal force.
            N_m = -1;
            continue;
          }
        // The contact of an edge node is bilateral: its walls hold it in
        // every step, and the memory relaxes wherever the wall pushed in
        // the last step too (N_m >= 0).
        const double now = impulses[j] / dt * m;
        impulses[j] =
          law->normal_stress_memory().remember(N_m, true, now, slip, dt) / m *
          dt;
      }
    return true;
  }


  template <int dim>
  std::array<double, 2>
  BoundaryConditions<dim>::edge_pore_water_relief(const unsigned int      k,
                                                  const PoreWaterAtNodes &water,
                                                  const NodalVector      &mass,
                                                  const double dt) const
  {
    // apply_friction()'s relief, wall by wall: a vector u is split onto
    // the two walls' normals n_j by the Gram system G c = (u.n_0, u.n_1),
    // as WallFriction::edge_frictional_acceleration() splits the
    // skeleton's push.
    const auto           &node = nodes[k];
    const auto           &n    = node.edge_normals;
    const double          g01  = n[0] * n[1];
    const double          det  = 1 - g01 * g01;
    std::array<double, 2> relief{{0., 0.}};
    const NodeWater       w   = node_water(node, water);
    const double          m_s = mass.local_element(node.local_dofs[0]);
    if (det <= 0 || w.m_w <= 0 || m_s <= 0)
      return relief;
    const auto split = [&](const Tensor<1, dim> &u) {
      const double u0 = u * n[0], u1 = u * n[1];
      return std::array<double, 2>{
        {(u0 - g01 * u1) / det, (u1 - g01 * u0) / det}};
    };
    // The water's own push on each wall (without the drag), its push
    // after the drag, and the drag's force on it, per wall.
    const auto own   = split(w.m_w * w.v_w / dt + w.F_w);
    const auto after = split(w.m_w * w.v_w_new / dt);
    const auto drag  = split(w.m_w * (w.v_w_new - w.v_w) / dt - w.F_w);
    for (unsigned int j = 0; j < 2; ++j)
      relief[j] = pore_water_relief(water_drains_along(k, n[j]),
                                    own[j] +
                                      water.excess_push(node.local_dofs, n[j]),
                                    after[j],
                                    drag[j],
                                    w.n_i,
                                    m_s);
    return relief;
  }


  template <int dim>
  typename BoundaryConditions<dim>::NodeWater
  BoundaryConditions<dim>::node_water(const ConstrainedNode  &node,
                                      const PoreWaterAtNodes &water)
  {
    NodeWater          w;
    const unsigned int i0 = node.local_dofs[0];
    w.m_w                 = water.mass.local_element(i0);
    w.n_i                 = water.porosity.local_element(i0);
    for (unsigned int c = 0; c < dim; ++c)
      {
        const unsigned int i = node.local_dofs[c];
        w.v_w[c]             = water.brought_velocity.local_element(i);
        w.v_w_new[c]         = water.new_velocity.local_element(i);
        w.F_w[c]             = water.force.local_element(i);
      }
    return w;
  }


  template <int dim>
  double
  BoundaryConditions<dim>::pore_water_relief(const bool   drains,
                                             const double own,
                                             const double after,
                                             const double drag,
                                             const double n_i,
                                             const double m_s)
  {
    if (drains)
      return -drag / m_s;
    return n_i > 0 ? (std::max(own, 0.) / n_i - std::max(after, 0.)) / m_s : 0.;
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::water_drains_along(const unsigned int    k,
                                              const Tensor<1, dim> &n) const
  {
    if (!separate_water_walls)
      return false;
    const unsigned int w = water_node_of_node[k];
    if (w == numbers::invalid_unsigned_int)
      return true;
    // The water's constraint leaves the wall's normal free.
    return (water_nodes[w].projector * n) * n > 0.5;
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::does_work() const
  {
    return std::any_of(specs.begin(), specs.end(), [](const auto &spec) {
      return (spec.type == BoundaryType::velocity &&
              spec.local_velocity.norm() > 0) ||
             (carries_traction(spec.type) && spec.traction.norm() > 0) ||
             !spec.input_velocity.empty();
    });
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::has_frictional_wall_without_memory() const
  {
    return std::any_of(specs.begin(), specs.end(), [](const auto &spec) {
      return spec.type == BoundaryType::friction &&
             !spec.law->normal_stress_memory().active();
    });
  }


  template class BoundaryConditions<2>;
  template class BoundaryConditions<3>;
} // namespace MPM
