#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/boundary_conditions.h>

#include <cmath>

namespace MPM
{
  namespace
  {
    /**
     * Tangent of the 2D local frame: the outward normal turned by +90
     * degrees, so that on a bed with outward normal (0, -1) the tangent is
     * +x.
     */
    template <int dim>
    Tensor<1, dim>
    tangent_2d(const Tensor<1, dim> &n)
    {
      Tensor<1, dim> t;
      t[0] = -n[1];
      t[1] = n[0];
      return t;
    }

    /// Normals closer than this angle are merged at a corner node.
    const double merge_cosine = std::cos(10. * M_PI / 180.);
  } // namespace


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
    return names;
  }


  template <int dim>
  void
  BoundaryConditions<dim>::declare_parameters(
    ParameterHandler               &prm,
    const std::vector<std::string> &names)
  {
    declare_name_list(prm);
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
                            "free|fixed|slip|friction|velocity"),
                          "free; fixed (zero velocity); slip (zero normal "
                          "velocity); friction (zero normal velocity and "
                          "Coulomb friction); velocity (prescribed normal and "
                          "tangential velocity, 2D).");
        prm.declare_entry("Friction coefficient",
                          "0",
                          Patterns::Double(0),
                          "Coulomb friction coefficient mu >= 0 (Type = "
                          "friction).");
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
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }


  template <int dim>
  void
  BoundaryConditions<dim>::parse_parameters(ParameterHandler &prm)
  {
    const auto names = read_name_list(prm);
    prm.enter_subsection("Boundary conditions");
    for (const auto &name : names)
      {
        const std::string path = "Boundary conditions/" + name + "/";
        prm.enter_subsection(name);
        Spec s;
        s.name = name;
        for (const int id : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Boundary ids"))))
          s.ids.push_back(id);
        const std::string type = prm.get("Type");
        s.type = type == "free"     ? Type::free :
                 type == "fixed"    ? Type::fixed :
                 type == "slip"     ? Type::slip :
                 type == "friction" ? Type::friction :
                                      Type::velocity;
        s.friction_coefficient = prm.get_double("Friction coefficient");
        s.normal_from_mesh     = prm.get("Normal") == "mesh";
        if (!s.normal_from_mesh)
          {
            s.given_normal =
              parse_point<dim>(prm.get("Outward normal"), path + "Outward normal");
            check_input(s.given_normal.norm() > 0,
                        path + "Outward normal must not be zero.");
            s.given_normal /= s.given_normal.norm();
          }
        if (s.type == Type::velocity)
          {
            check_input(dim == 2,
                        path + "Type = velocity is implemented in 2D only.");
            s.local_velocity = parse_point<dim>(prm.get("Velocity"),
                                                 path + "Velocity");
          }
        prm.leave_subsection();
        specs.push_back(s);
      }
    prm.leave_subsection();
  }


  template <int dim>
  double
  BoundaryConditions<dim>::friction_coefficient(const std::string &name) const
  {
    for (const auto &s : specs)
      if (s.name == name)
        return s.type == Type::friction ? s.friction_coefficient : 0.;
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
  }


  template <int dim>
  void
  BoundaryConditions<dim>::setup(const BackgroundGrid<dim> &grid,
                                 const NodalVector         &layout)
  {
    // The contact state is kept by location through a new setup (after
    // repartitioning, a node may now live on another rank).
    const std::vector<ContactLocations> contact_before =
      Utilities::MPI::all_gather(grid.triangulation.get_communicator(),
                                 contact_locations());
    nodes.clear();
    contact_state.clear();
    normal_constraints.clear();
    normal_constraints.reinit(grid.locally_relevant_dofs);
    if (specs.empty())
      {
        normal_constraints.close();
        return;
      }

    // 1. For each boundary: the face-size weighted sum of the outward
    //    normals of its faces at each node, and the nodes it touches,
    //    summed over ranks so that nodes on partition boundaries agree.
    std::vector<NodalVector> normal_sum(specs.size(), layout);
    std::vector<NodalVector> touches(specs.size(), layout);
    for (auto &v : normal_sum)
      v = 0;
    for (auto &v : touches)
      v = 0;

    FEFaceValues<dim> fe_face_values(grid.mapping,
                                     grid.fe,
                                     QGauss<dim - 1>(1),
                                     update_normal_vectors | update_JxW_values);
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const types::boundary_id id = cell->face(f)->boundary_id();
            bool                     reinitialized = false;
            for (unsigned int s = 0; s < specs.size(); ++s)
              {
                if (std::find(specs[s].ids.begin(), specs[s].ids.end(), id) ==
                    specs[s].ids.end())
                  continue;
                if (!reinitialized)
                  fe_face_values.reinit(cell, f);
                reinitialized           = true;
                const Tensor<1, dim> nA = fe_face_values.normal_vector(0) *
                                          fe_face_values.JxW(0);
                for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const auto dof = cell->face(f)->vertex_dof_index(v, c);
                      normal_sum[s](dof) += nA[c];
                      touches[s](dof) += 1;
                    }
              }
          }
      }
    for (unsigned int s = 0; s < specs.size(); ++s)
      {
        normal_sum[s].compress(VectorOperation::add);
        normal_sum[s].update_ghost_values();
        touches[s].compress(VectorOperation::add);
        touches[s].update_ghost_values();
      }

    // 2. The constraint normals of each locally relevant node, by the
    //    corner rule of the class documentation.
    struct NodeConstraint
    {
      std::array<types::global_dof_index, dim> dofs;
      Point<dim>                               location;
      std::vector<Tensor<1, dim>>              normals;
      std::vector<double>                      values;
      bool                                     frictional = false;
      double                                   mu         = 0;
      bool                                     edge_friction = false;
      std::array<Tensor<1, dim>, 2>            edge_normals;
      std::array<double, 2>                    edge_mu{};
    };
    std::vector<NodeConstraint> node_constraints;
    std::vector<bool>           visited(layout.locally_owned_size() +
                                  layout.get_partitioner()->n_ghost_indices(),
                                false);

    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        for (const unsigned int v : cell->vertex_indices())
          {
            NodeConstraint nc;
            nc.location = cell->vertex(v);
            for (unsigned int c = 0; c < dim; ++c)
              nc.dofs[c] = cell->vertex_dof_index(v, c);
            const unsigned int local0 =
              layout.get_partitioner()->global_to_local(nc.dofs[0]);
            if (visited[local0])
              continue;
            visited[local0] = true;

            bool                        fixed = false, prescribed = false;
            Tensor<1, dim>              prescribed_velocity;
            std::vector<Tensor<1, dim>> cluster_sum;
            std::vector<double>         cluster_mu;
            std::vector<bool>           cluster_friction;
            for (unsigned int s = 0; s < specs.size(); ++s)
              {
                if (touches[s].local_element(local0) == 0 ||
                    specs[s].type == Type::free)
                  continue;
                Tensor<1, dim> weighted;
                for (unsigned int c = 0; c < dim; ++c)
                  weighted[c] = normal_sum[s].local_element(
                    layout.get_partitioner()->global_to_local(nc.dofs[c]));
                if (!specs[s].normal_from_mesh)
                  weighted = grid.to_mesh_frame(specs[s].given_normal) *
                             std::max(weighted.norm(), 1e-300);
                if (specs[s].type == Type::fixed)
                  fixed = true;
                else if (weighted.norm() == 0)
                  fixed = true; // opposite faces cancel: a knife edge
                else if (specs[s].type == Type::velocity)
                  {
                    const Tensor<1, dim> n = weighted / weighted.norm();
                    prescribed          = true;
                    prescribed_velocity = specs[s].local_velocity[0] * n +
                                          specs[s].local_velocity[1] *
                                            tangent_2d(n);
                  }
                else
                  {
                    const Tensor<1, dim> n = weighted / weighted.norm();
                    bool                 merged = false;
                    for (unsigned int k = 0; k < cluster_sum.size(); ++k)
                      if (std::abs(n * cluster_sum[k]) >
                          merge_cosine * cluster_sum[k].norm())
                        {
                          cluster_sum[k] += weighted;
                          if (specs[s].type == Type::friction)
                            {
                              cluster_friction[k] = true;
                              cluster_mu[k] =
                                std::max(cluster_mu[k],
                                         specs[s].friction_coefficient);
                            }
                          merged = true;
                          break;
                        }
                    if (!merged)
                      {
                        cluster_sum.push_back(weighted);
                        cluster_friction.push_back(specs[s].type ==
                                                   Type::friction);
                        cluster_mu.push_back(specs[s].friction_coefficient);
                      }
                  }
              }

            if (!fixed && !prescribed && cluster_sum.size() >= dim)
              fixed = true;
            if (fixed || prescribed)
              {
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    Tensor<1, dim> e;
                    e[c] = 1;
                    nc.normals.push_back(e);
                    nc.values.push_back(fixed ? 0. : prescribed_velocity[c]);
                  }
              }
            else if (cluster_sum.size() > 0)
              {
                for (const auto &n : cluster_sum)
                  {
                    nc.normals.push_back(n / n.norm());
                    nc.values.push_back(0.);
                  }
                if (cluster_sum.size() == 1 && cluster_friction[0])
                  {
                    nc.frictional = true;
                    nc.mu         = cluster_mu[0];
                  }
                else if (cluster_sum.size() == 2 &&
                         (cluster_friction[0] || cluster_friction[1]))
                  {
                    // A 3D edge (2D nodes with two normals are fixed).
                    nc.edge_friction = true;
                    for (unsigned int j = 0; j < 2; ++j)
                      {
                        nc.edge_normals[j] =
                          cluster_sum[j] / cluster_sum[j].norm();
                        nc.edge_mu[j] =
                          cluster_friction[j] ? cluster_mu[j] : 0.;
                      }
                  }
              }
            if (!nc.normals.empty())
              node_constraints.push_back(nc);
          }
      }

    // 3. The constraints as AffineConstraints lines: Gauss-Jordan
    //    elimination of the rows n . v = b with column pivoting expresses
    //    the pivot components through the free ones.
    for (const auto &nc : node_constraints)
      {
        const unsigned int               k = nc.normals.size();
        std::vector<std::array<double, dim>> A(k);
        std::vector<double>                  b = nc.values;
        for (unsigned int r = 0; r < k; ++r)
          for (unsigned int c = 0; c < dim; ++c)
            A[r][c] = nc.normals[r][c];
        std::array<bool, dim>     is_pivot{};
        std::vector<unsigned int> pivot(k);
        for (unsigned int r = 0; r < k; ++r)
          {
            unsigned int p = dim;
            for (unsigned int c = 0; c < dim; ++c)
              if (!is_pivot[c] && (p == dim || std::abs(A[r][c]) > std::abs(A[r][p])))
                p = c;
            AssertThrow(p < dim && std::abs(A[r][p]) > 1e-12,
                        ExcMessage("Linearly dependent boundary normals."));
            is_pivot[p]        = true;
            pivot[r]           = p;
            const double scale = A[r][p];
            for (unsigned int c = 0; c < dim; ++c)
              A[r][c] /= scale;
            b[r] /= scale;
            for (unsigned int q = 0; q < k; ++q)
              if (q != r && A[q][p] != 0)
                {
                  const double factor = A[q][p];
                  for (unsigned int c = 0; c < dim; ++c)
                    A[q][c] -= factor * A[r][c];
                  b[q] -= factor * b[r];
                }
          }
        for (unsigned int r = 0; r < k; ++r)
          {
            const auto row = nc.dofs[pivot[r]];
            normal_constraints.add_line(row);
            for (unsigned int c = 0; c < dim; ++c)
              if (!is_pivot[c] && std::abs(A[r][c]) > 1e-15)
                normal_constraints.add_entry(row, nc.dofs[c], -A[r][c]);
            normal_constraints.set_inhomogeneity(row, b[r]);
          }
      }
    normal_constraints.close();

    // 4. The orthogonal projector of each node, read back from the
    //    AffineConstraints lines: a line v_p = sum_c a_c v_c + b is the row
    //    (e_p - sum_c a_c e_c) . v = b.
    for (const auto &nc : node_constraints)
      {
        ConstrainedNode node;
        for (unsigned int c = 0; c < dim; ++c)
          node.local_dofs[c] =
            layout.get_partitioner()->global_to_local(nc.dofs[c]);
        std::vector<Tensor<1, dim>> rows;
        std::vector<double>         rhs;
        for (unsigned int c = 0; c < dim; ++c)
          if (normal_constraints.is_constrained(nc.dofs[c]))
            {
              Tensor<1, dim> row;
              row[c] = 1;
              for (const auto &[dof, weight] :
                   *normal_constraints.get_constraint_entries(nc.dofs[c]))
                {
                  const auto it = std::find(nc.dofs.begin(), nc.dofs.end(), dof);
                  Assert(it != nc.dofs.end(),
                         ExcMessage("A normal constraint couples two nodes."));
                  row[it - nc.dofs.begin()] -= weight;
                }
              rows.push_back(row);
              rhs.push_back(normal_constraints.get_inhomogeneity(nc.dofs[c]));
            }
        const unsigned int k = rows.size();
        FullMatrix<double> gram(k, k);
        for (unsigned int i = 0; i < k; ++i)
          for (unsigned int j = 0; j < k; ++j)
            gram(i, j) = rows[i] * rows[j];
        gram.gauss_jordan();
        node.projector = unit_symmetric_tensor<dim>();
        for (unsigned int i = 0; i < k; ++i)
          for (unsigned int j = 0; j < k; ++j)
            {
              node.projector -= gram(i, j) * outer_product(rows[i], rows[j]);
              node.offset += gram(i, j) * rhs[j] * rows[i];
            }
        node.frictional           = nc.frictional;
        node.normal               = nc.normals[0];
        node.friction_coefficient = nc.mu;
        node.location             = nc.location;
        node.edge_friction        = nc.edge_friction;
        node.edge_normals         = nc.edge_normals;
        node.edge_mu              = nc.edge_mu;
        nodes.push_back(node);
      }
    contact_state.assign(nodes.size(), ContactState::free);
    set_contact(merge(contact_before));
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
          if (v * nodes[k].normal <= 0)
            contact_state[k] = ContactState::free;
          else if (contact_state[k] != ContactState::stuck)
            contact_state[k] = ContactState::sliding;
        }
    project_velocity(velocity, Contact::by_velocity);
  }


  template <int dim>
  typename BoundaryConditions<dim>::ContactLocations
  BoundaryConditions<dim>::contact_locations() const
  {
    ContactLocations locations;
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (contact_state[k] != ContactState::free)
        locations[contact_state[k] == ContactState::stuck].push_back(
          nodes[k].location);
    return locations;
  }


  template <int dim>
  void
  BoundaryConditions<dim>::set_contact(const ContactLocations &locations)
  {
    // Exact comparison: the locations are vertices of the same mesh.
    const auto less = [](const Point<dim> &a, const Point<dim> &b) {
      return std::lexicographical_compare(a.begin_raw(),
                                          a.end_raw(),
                                          b.begin_raw(),
                                          b.end_raw());
    };
    std::array<std::vector<Point<dim>>, 2> sorted = locations;
    for (auto &list : sorted)
      std::sort(list.begin(), list.end(), less);
    const auto contains = [&](const unsigned int list, const Point<dim> &x) {
      return std::binary_search(sorted[list].begin(), sorted[list].end(), x, less);
    };
    for (unsigned int k = 0; k < nodes.size(); ++k)
      contact_state[k] =
        !(nodes[k].frictional || nodes[k].edge_friction) ?
                                         ContactState::free :
        contains(1, nodes[k].location) ? ContactState::stuck :
        contains(0, nodes[k].location) ? ContactState::sliding :
                                         ContactState::free;
  }


  template <int dim>
  Tensor<1, dim>
  BoundaryConditions<dim>::frictional_acceleration(const Tensor<1, dim> &v,
                                                   const Tensor<1, dim> &a,
                                                   const Tensor<1, dim> &n,
                                                   const double          mu,
                                                   const double          dt,
                                                   bool *const           sticks)
  {
    if (sticks != nullptr)
      *sticks = false;
    // Normal velocity change per unit time that the wall must remove to keep
    // v_n = 0 at the end of the step: the normal reaction per unit mass. The
    // wall only pushes, so friction acts only if it is positive.
    const double v_n      = v * n;
    const double a_n      = a * n;
    const double reaction = v_n / dt + a_n;
    if (reaction <= 0)
      return a;

    // Coulomb's law integrated by backward Euler: the tangential velocity
    // the node would reach without friction (the trial velocity) is
    // reduced by at most mu * reaction * dt. If that stops it, the node
    // sticks (static friction, or kinetic friction that would otherwise
    // reverse the motion within the step); else it slides on with friction
    // opposing the trial velocity.
    const Tensor<1, dim> v_t       = v - v_n * n;
    const Tensor<1, dim> v_t_trial = v_t + dt * (a - a_n * n);
    const double         speed     = v_t_trial.norm();
    const double         capacity  = mu * reaction * dt;
    const Tensor<1, dim> v_t_new =
      speed <= capacity ? Tensor<1, dim>() :
                          (1. - capacity / speed) * v_t_trial;
    if (sticks != nullptr)
      *sticks = speed <= capacity;
    return a_n * n + (v_t_new - v_t) / dt;
  }


  template <int dim>
  Tensor<1, dim>
  BoundaryConditions<dim>::edge_frictional_acceleration(
    const Tensor<1, dim>                &v,
    const Tensor<1, dim>                &a,
    const std::array<Tensor<1, dim>, 2> &n,
    const std::array<double, 2>         &mu,
    const double                         dt,
    bool *const                          sticks)
  {
    if (sticks != nullptr)
      *sticks = false;
    // Wall impulses lambda_j n_j that bring w onto the edge:
    // G lambda = -N w with the Gram matrix G of the normals.
    const Tensor<1, dim> w   = v + dt * a;
    const double         g01 = n[0] * n[1];
    const double         det = 1 - g01 * g01;
    if (det <= 0)
      return a;
    const double r0 = -(n[0] * w), r1 = -(n[1] * w);
    const std::array<double, 2> lambda = {{(r0 - g01 * r1) / det,
                                           (r1 - g01 * r0) / det}};
    double capacity = 0;
    for (unsigned int j = 0; j < 2; ++j)
      capacity += mu[j] * std::max(0., -lambda[j]);
    if (capacity <= 0)
      return a;
    // Components along the edge (the free direction) and across it.
    const auto along = [&](const Tensor<1, dim> &u) {
      return u + ((n[0] * u) * (g01 * n[1] - n[0]) +
                  (n[1] * u) * (g01 * n[0] - n[1])) /
                   det;
    };
    const Tensor<1, dim> w_t   = along(w);
    const double         speed = w_t.norm();
    const Tensor<1, dim> w_t_new =
      speed <= capacity ? Tensor<1, dim>() : (1. - capacity / speed) * w_t;
    if (sticks != nullptr)
      *sticks = speed <= capacity;
    return (a - along(a)) + (w_t_new - along(v)) / dt;
  }


  template <int dim>
  void
  BoundaryConditions<dim>::apply_friction(const NodalVector &mass,
                                          const NodalVector &velocity,
                                          NodalVector       &acceleration,
                                          const double       dt)
  {
    for (unsigned int k = 0; k < nodes.size(); ++k)
      {
        const auto &node = nodes[k];
        if (!node.frictional && !node.edge_friction)
          continue;
        contact_state[k] = ContactState::free;
        if (mass.local_element(node.local_dofs[0]) <= 0)
          continue;
        Tensor<1, dim> v, a;
        for (unsigned int c = 0; c < dim; ++c)
          {
            v[c] = velocity.local_element(node.local_dofs[c]);
            a[c] = acceleration.local_element(node.local_dofs[c]);
          }
        bool sticks = false;
        a           = node.frictional ?
                        frictional_acceleration(
                          v, a, node.normal, node.friction_coefficient, dt, &sticks) :
                        edge_frictional_acceleration(
                          v, a, node.edge_normals, node.edge_mu, dt, &sticks);
        if (sticks)
          contact_state[k] = ContactState::stuck;
        for (unsigned int c = 0; c < dim; ++c)
          acceleration.local_element(node.local_dofs[c]) = a[c];
      }
  }


  template <int dim>
  bool
  BoundaryConditions<dim>::does_work() const
  {
    return std::any_of(specs.begin(), specs.end(), [](const Spec &spec) {
      return spec.type == Type::velocity && spec.local_velocity.norm() > 0;
    });
  }


  template class BoundaryConditions<2>;
  template class BoundaryConditions<3>;
} // namespace MPM
