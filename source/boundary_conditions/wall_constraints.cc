#include <deal.II/lac/full_matrix.h>

#include <mpm/boundary_conditions/wall_constraints.h>

#include <algorithm>
#include <cmath>

namespace MPM
{
  template <int dim>
  void
  make_wall_constraints(const std::vector<NodeFrame<dim>> &frames,
                        const IndexSet                    &relevant,
                        AffineConstraints<double>         &constraints)
  {
    constraints.clear();
    constraints.reinit(relevant);
    for (const auto &nc : frames)
      {
        const unsigned int                   k = nc.normals.size();
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
              if (!is_pivot[c] &&
                  (p == dim || std::abs(A[r][c]) > std::abs(A[r][p])))
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
            constraints.add_line(row);
            for (unsigned int c = 0; c < dim; ++c)
              if (!is_pivot[c] && std::abs(A[r][c]) > 1e-15)
                constraints.add_entry(row, nc.dofs[c], -A[r][c]);
            constraints.set_inhomogeneity(row, b[r]);
          }
      }
    constraints.close();
  }


  template <int dim>
  std::vector<ConstrainedNode<dim>>
  make_projections(const std::vector<NodeFrame<dim>> &frames,
                   const AffineConstraints<double>   &constraints,
                   const NodalVector                 &layout)
  {
    std::vector<ConstrainedNode<dim>> nodes;
    for (const auto &nc : frames)
      {
        ConstrainedNode<dim> node;
        for (unsigned int c = 0; c < dim; ++c)
          node.local_dofs[c] =
            layout.get_partitioner()->global_to_local(nc.dofs[c]);
        std::vector<Tensor<1, dim>> rows;
        std::vector<double>         rhs;
        for (unsigned int c = 0; c < dim; ++c)
          if (constraints.is_constrained(nc.dofs[c]))
            {
              Tensor<1, dim> row;
              row[c] = 1;
              for (const auto &[dof, weight] :
                   *constraints.get_constraint_entries(nc.dofs[c]))
                {
                  const auto it =
                    std::find(nc.dofs.begin(), nc.dofs.end(), dof);
                  Assert(it != nc.dofs.end(),
                         ExcMessage("A normal constraint couples two nodes."));
                  row[it - nc.dofs.begin()] -= weight;
                }
              rows.push_back(row);
              rhs.push_back(constraints.get_inhomogeneity(nc.dofs[c]));
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
        node.frictional    = nc.frictional;
        node.normal        = nc.normals[0];
        node.law           = nc.law;
        node.geometry      = nc.geometry;
        node.location      = nc.location;
        node.edge_friction = nc.edge_friction;
        node.edge_normals  = nc.edge_normals;
        node.edge_laws     = nc.edge_laws;
        node.edge_geometry = nc.edge_geometry;
        nodes.push_back(node);
      }
    return nodes;
  }


  template void
  make_wall_constraints(const std::vector<NodeFrame<2>> &,
                        const IndexSet &,
                        AffineConstraints<double> &);
  template void
  make_wall_constraints(const std::vector<NodeFrame<3>> &,
                        const IndexSet &,
                        AffineConstraints<double> &);
  template std::vector<ConstrainedNode<2>>
  make_projections(const std::vector<NodeFrame<2>> &,
                   const AffineConstraints<double> &,
                   const NodalVector &);
  template std::vector<ConstrainedNode<3>>
  make_projections(const std::vector<NodeFrame<3>> &,
                   const AffineConstraints<double> &,
                   const NodalVector &);
} // namespace MPM
