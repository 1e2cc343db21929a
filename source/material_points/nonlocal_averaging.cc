#include <deal.II/base/mpi.h>

#include <mpm/material_points/nonlocal_averaging.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/parallel/thread_chunks.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace MPM
{
  template <int dim>
  void
  NonlocalGrid<dim>::reinit(const Point<dim>  &lower,
                            const Point<dim>  &upper,
                            const double       radius,
                            const std::string &material_name)
  {
    Assert(radius > 0, ExcMessage("The non-local radius must be positive."));
    this->radius = radius;
    spacing      = radius / nodes_per_radius;
    double n     = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        // The origin at a multiple of the spacing: the grid, and so the
        // averages, depend on the points' positions alone, not on the box
        // they happen to fill in this step.
        origin[d] = std::floor((lower[d] - radius) / spacing) * spacing;
        const double cells =
          std::ceil((upper[d] + radius - origin[d]) / spacing) + 1;
        n *= cells + 1;
        n_nodes_per_direction[d] =
          static_cast<unsigned int>(std::min(cells + 1, 4e9));
      }
    if (n > 1e8)
      throw std::runtime_error(
        "The non-local average of material '" + material_name + "' (radius " +
        std::to_string(radius) + " m) would need a grid of " +
        std::to_string(n) + " nodes (spacing " + std::to_string(spacing) +
        " m, a quarter of the radius, over the material's points): the "
        "radius is too small for the extent of the material. Increase the "
        "radius or split the material.");
    sums.assign(static_cast<std::size_t>(n), {{0., 0.}});
  }


  template <int dim>
  void
  NonlocalGrid<dim>::add(const Point<dim> &x,
                         const double      volume,
                         const double      value)
  {
    add_rows(x, volume, value, 0, n_nodes_per_direction[dim - 1]);
  }


  template <int dim>
  unsigned int
  NonlocalGrid<dim>::row_of(const Point<dim> &x) const
  {
    return static_cast<unsigned int>(
      std::floor((x[dim - 1] - origin[dim - 1]) / spacing));
  }


  template <int dim>
  void
  NonlocalGrid<dim>::add_points(const std::vector<Point<dim>> &x,
                                const std::vector<double>     &volume,
                                const std::vector<double>     &value)
  {
    AssertDimension(x.size(), volume.size());
    AssertDimension(x.size(), value.size());
    // The points by their row of nodes along the last direction (a stable
    // counting sort): a node then receives its contributions in the order
    // (row of the point, index), whichever slab of rows a thread adds, so
    // that the sums do not depend on the number of threads.
    const unsigned int n_rows = n_nodes_per_direction[dim - 1];
    row_start.assign(n_rows + 1, 0);
    for (const auto &p : x)
      ++row_start[row_of(p) + 1];
    for (unsigned int r = 0; r < n_rows; ++r)
      row_start[r + 1] += row_start[r];
    order.resize(x.size());
    {
      std::vector<unsigned int> next(row_start.begin(), row_start.end() - 1);
      for (unsigned int i = 0; i < x.size(); ++i)
        order[next[row_of(x[i])]++] = i;
    }
    // Slabs of rows, each added by one thread: the points whose rows lie
    // within nodes_per_radius of the slab, restricted to its rows. One slab
    // per thread (one on one thread), each holding about the same number
    // of points (not of rows: a slope's lower rows hold most of its
    // points) and at least nodes_per_radius + 1 rows. Fewer slabs because
    // a point's set-up is repeated in every slab within its reach: on one
    // thread two slabs of rows cost the slope runout a quarter more
    // averaging than one, and on two threads four slabs gained nothing
    // over one thread. Any partition into slabs gives the same sums, so
    // the results do not depend on the number of threads.
    const unsigned int n_points = x.size();
    const std::uint64_t n_slabs_wanted =
      n_points < 512 || MultithreadInfo::n_threads() == 1 ?
        1 :
        MultithreadInfo::n_threads();
    slab_start.assign(1, 0);
    for (unsigned int r = 1; r < n_rows; ++r)
      if (r - slab_start.back() > nodes_per_radius &&
          row_start[r] < n_points &&
          row_start[r] * n_slabs_wanted >=
            slab_start.size() * std::uint64_t(n_points))
        slab_start.push_back(r);
    slab_start.push_back(n_rows);
    for_each_chunk(slab_start.size() - 1,
                   1,
                   [&](const unsigned int slab,
                       const unsigned int,
                       const unsigned int) {
                     const unsigned int begin = slab_start[slab];
                     const unsigned int end   = slab_start[slab + 1];
                     const unsigned int first_row =
                       begin > nodes_per_radius ? begin - nodes_per_radius : 0;
                     const unsigned int last_row =
                       std::min(n_rows, end + nodes_per_radius + 1);
                     for (unsigned int k = row_start[first_row];
                          k < row_start[last_row];
                          ++k)
                       {
                         const unsigned int i = order[k];
                         add_rows(x[i], volume[i], value[i], begin, end);
                       }
                   });
  }


  template <int dim>
  void
  NonlocalGrid<dim>::add_rows(const Point<dim>  &x,
                              const double       volume,
                              const double       value,
                              const unsigned int row_begin,
                              const unsigned int row_end)
  {
    // The box of nodes within R of x in each direction (at most
    // 2 nodes_per_radius + 1 per direction) and, per direction, the
    // squared distances over R^2 of its node lines. The weight of a node
    // is then (1 - sum of its lines' terms)^2 where that is positive: no
    // square root per node, and the innermost loop runs without a branch
    // over the contiguous nodes of a line that lie inside the ball.
    constexpr unsigned int     max_width = 2 * nodes_per_radius + 2;
    const double               inverse_r2 = 1. / (radius * radius);
    std::array<int, dim>       first;
    std::array<unsigned int, dim> width;
    std::array<std::array<double, max_width>, dim> term;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double s  = (x[d] - origin[d]) / spacing;
        const int    lo = static_cast<int>(std::ceil(s - nodes_per_radius));
        const int    hi = static_cast<int>(std::floor(s + nodes_per_radius));
        first[d]        = lo;
        width[d]        = static_cast<unsigned int>(hi - lo + 1);
        AssertIndexRange(width[d], max_width + 1);
        AssertIndexRange(hi, n_nodes_per_direction[d]);
        Assert(lo >= 0, ExcInternalError());
        for (unsigned int i = 0; i < width[d]; ++i)
          {
            const double dx = origin[d] + (lo + int(i)) * spacing - x[d];
            term[d][i]      = dx * dx * inverse_r2;
          }
      }
    const double wv = volume * value;
    // A line of nodes along the first direction: only the nodes inside the
    // ball (term < rest; term is convex along the line, so they are a
    // contiguous range, found from both ends). The nodes outside it would
    // add an exact 0: skipping them leaves the same sums, and the ball is
    // about 60 % of the box in 2D, 45 % in 3D.
    const auto add_line = [&](const double rest, const std::size_t start) {
      unsigned int begin = 0, end = width[0];
      while (begin < end && term[0][begin] >= rest)
        ++begin;
      while (end > begin && term[0][end - 1] >= rest)
        --end;
      auto *node = &sums[start];
      for (unsigned int i = begin; i < end; ++i)
        {
          const double q = rest - term[0][i];
          const double w = q * q;
          node[i][0] += w * wv;
          node[i][1] += w * volume;
        }
    };
    // Only the rows of the last direction in [row_begin, row_end).
    const int          last_first = first[dim - 1];
    const unsigned int outer_begin =
      std::max(0, int(row_begin) - last_first);
    const unsigned int outer_end = static_cast<unsigned int>(std::max(
      0, std::min(int(width[dim - 1]), int(row_end) - last_first)));
    const std::size_t n0 = n_nodes_per_direction[0];
    if constexpr (dim == 2)
      {
        for (unsigned int j = outer_begin; j < outer_end; ++j)
          {
            const double rest = 1. - term[1][j];
            if (rest > 0)
              add_line(rest, first[0] + n0 * (first[1] + j));
          }
      }
    else
      {
        const std::size_t n1 = n_nodes_per_direction[1];
        for (unsigned int k = outer_begin; k < outer_end; ++k)
          for (unsigned int j = 0; j < width[1]; ++j)
            {
              const double rest = 1. - term[2][k] - term[1][j];
              if (rest > 0)
                add_line(rest,
                         first[0] + n0 * (first[1] + j + n1 * (first[2] + k)));
            }
      }
  }


  template <int dim>
  void
  NonlocalGrid<dim>::sum_over(const MPI_Comm comm)
  {
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
      return;
    const ArrayView<double> values(sums.empty() ? nullptr : &sums[0][0],
                                   2 * sums.size());
    Utilities::MPI::sum(ArrayView<const double>(values.data(), values.size()),
                        comm,
                        values);
  }


  template <int dim>
  double
  NonlocalGrid<dim>::average(const Point<dim> &x) const
  {
    std::array<unsigned int, dim> base;
    std::array<double, dim>       fraction;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double s = (x[d] - origin[d]) / spacing;
        const double b = std::floor(s);
        base[d]        = static_cast<unsigned int>(b);
        fraction[d]    = s - b;
      }
    double numerator = 0, denominator = 0;
    for (unsigned int corner = 0; corner < (1u << dim); ++corner)
      {
        double      phi   = 1;
        std::size_t index = 0, stride = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const unsigned int bit = (corner >> d) & 1u;
            phi *= bit ? fraction[d] : 1. - fraction[d];
            index += (base[d] + bit) * stride;
            stride *= n_nodes_per_direction[d];
          }
        AssertIndexRange(index, sums.size());
        numerator += phi * sums[index][0];
        denominator += phi * sums[index][1];
      }
    Assert(denominator > 0,
           ExcMessage("A non-local average at a point with no points near."));
    return numerator / denominator;
  }


  template <int dim>
  NonlocalAveraging<dim>::NonlocalAveraging(const MaterialLibrary &materials)
    : materials(materials)
  {}


  template <int dim>
  bool
  NonlocalAveraging<dim>::active() const
  {
    for (unsigned int m = 0; m < materials.size(); ++m)
      if (materials[m].model->nonlocal_variable() != nullptr)
        return true;
    return false;
  }


  template <int dim>
  void
  NonlocalAveraging<dim>::update(
    Particles::ParticleHandler<dim> &particle_handler,
    const MPI_Comm                   comm)
  {
    using Layout = PropertyLayout<dim>;
    for (unsigned int m = 0; m < materials.size(); ++m)
      {
        const auto *variable = materials[m].model->nonlocal_variable();
        if (variable == nullptr)
          continue;
        const unsigned int local = Layout::state + variable->local_variable;
        const unsigned int nonlocal =
          Layout::state + variable->nonlocal_variable;
        const double factor = variable->over_nonlocal_factor;

        // The material's points (one walk over the ParticleHandler; the
        // grid's passes then read these arrays), their box and largest
        // value over all ranks: [-lower, upper, max] reduced by one max.
        points.clear();
        locations.clear();
        volumes.clear();
        values.clear();
        std::vector<double> extent(2 * dim + 1,
                                   -std::numeric_limits<double>::max());
        for (auto &point : particle_handler)
          {
            const auto props = point.get_properties();
            if (static_cast<unsigned int>(props[Layout::material_id]) != m)
              continue;
            const Point<dim> x = point.get_location();
            for (unsigned int d = 0; d < dim; ++d)
              {
                extent[d]       = std::max(extent[d], -x[d]);
                extent[dim + d] = std::max(extent[dim + d], x[d]);
              }
            extent[2 * dim] = std::max(extent[2 * dim], props[local]);
            points.push_back(props.data());
            locations.push_back(x);
            volumes.push_back(props[Layout::volume]);
            values.push_back(props[local]);
          }
        Utilities::MPI::max(ArrayView<const double>(extent.data(), extent.size()),
                            comm,
                            ArrayView<double>(extent.data(), extent.size()));
        // No point of the material, or none has a value yet (the
        // variable only grows, so the regularised values are still the
        // zeros they started with).
        if (!(extent[2 * dim] > 0))
          continue;
        Point<dim> lower, upper;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lower[d] = -extent[d];
            upper[d] = extent[dim + d];
          }
        grid.reinit(lower, upper, variable->radius, materials[m].name);
        grid.add_points(locations, volumes, values);
        grid.sum_over(comm);
        const unsigned int n = points.size();
        for_each_chunk(n,
                       chunk_size_for(n),
                       [&](const unsigned int,
                           const unsigned int begin,
                           const unsigned int end) {
                         for (unsigned int i = begin; i < end; ++i)
                           points[i][nonlocal] = std::max(
                             0.,
                             (1. - factor) * values[i] +
                               factor * grid.average(locations[i]));
                       });
      }
  }


  template class NonlocalGrid<2>;
  template class NonlocalGrid<3>;
  template class NonlocalAveraging<2>;
  template class NonlocalAveraging<3>;
} // namespace MPM
