#include <deal.II/base/mpi.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/flume.h>
#include <mpm/postprocess/volume_quantiles.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>

namespace MPM
{
  namespace Postprocessors
  {
    template <int dim>
    void
    Flume<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Slope angle",
                        "31.4",
                        Patterns::Double(0, 90),
                        "Angle theta of the incline to the horizontal, in "
                        "degrees.");
      prm.declare_entry("Arc radius",
                        "0.1",
                        Patterns::Double(0),
                        "Radius R of the circular arc between the incline and "
                        "the runout, in m.");
      prm.declare_entry("Break in slope",
                        "0, 0",
                        Patterns::Anything(),
                        "x, y (m) of the point where the incline and the "
                        "runout, produced, meet.");
      prm.declare_entry("Bin width",
                        "0.01",
                        Patterns::Double(0),
                        "Width (m, along the bed) of the bins of the final "
                        "deposit profile.");
      prm.declare_entry("Stop speed",
                        "0.01",
                        Patterns::Double(0),
                        "The flow counts as stopped once the mean speed "
                        "(m/s) stays below this.");
      prm.declare_entry("Front tolerance",
                        "0.001",
                        Patterns::Double(0),
                        "The front counts as at rest from the output time "
                        "after which it stays within this distance (m) of "
                        "its final position.");
      declare_volume_fractions(
        prm,
        "The report also gives, for each fraction q here, the distance s "
        "along the bed within which the fraction q of the final deposit's "
        "point volume lies, counted from its tail (interpolated in the bins "
        "of the deposit profile): an end of the deposit that a few points "
        "run ahead of it do not move, unlike the front point.");
    }


    template <int dim>
    void
    Flume<dim>::parse_parameters(ParameterHandler &prm)
    {
      check_input(dim == 2, "Postprocess/flume is 2D only.");
      theta           = prm.get_double("Slope angle") * M_PI / 180;
      radius          = prm.get_double("Arc radius");
      bin_width       = prm.get_double("Bin width");
      stop_speed      = prm.get_double("Stop speed");
      front_tolerance = prm.get_double("Front tolerance");
      volume_fractions = parse_volume_fractions(prm);
      break_point = parse_point<2>(prm.get("Break in slope"),
                                   "Postprocess/flume/Break in slope");
    }


    template <int dim>
    std::pair<double, double>
    Flume<dim>::bed_coordinates(const double x, const double y) const
    {
      // Down-slope unit vector u and upward normal n of the incline; the
      // arc runs from T1 (on the incline) to T2 (on the runout), centre C.
      const double d = radius * std::tan(theta / 2), half = radius * theta / 2;
      const Tensor<1, 2> u({std::cos(theta), -std::sin(theta)});
      const Tensor<1, 2> n({std::sin(theta), std::cos(theta)});
      const Point<2>     p(x, y);
      const Point<2>     t1            = break_point - d * u;
      const Point<2>     t2            = break_point + Tensor<1, 2>({d, 0.});
      const Point<2>     c             = t2 + Tensor<1, 2>({0., radius});
      const double       along_incline = (p - t1) * u;
      if (along_incline <= 0)
        return {-half + along_incline, (p - t1) * n};
      if (p[0] >= t2[0])
        return {half + p[0] - t2[0], p[1] - t2[1]};
      // psi: angle from C -> T2 (straight down) towards C -> T1.
      const Tensor<1, 2> r   = p - c;
      const double       psi = std::clamp(std::atan2(-r[0], -r[1]), 0., theta);
      return {half - radius * psi, radius - r.norm()};
    }


    template <int dim>
    Point<2>
    Flume<dim>::bed_point(const double s) const
    {
      const double d = radius * std::tan(theta / 2), half = radius * theta / 2;
      const Tensor<1, 2> u({std::cos(theta), -std::sin(theta)});
      if (s <= -half)
        return break_point - d * u + (s + half) * u;
      if (s >= half)
        return break_point + Tensor<1, 2>({d + s - half, 0.});
      const double psi = (half - s) / radius;
      return break_point + Tensor<1, 2>({d - radius * std::sin(psi),
                                         radius - radius * std::cos(psi)});
    }


    template <int dim>
    typename Flume<dim>::Sample
    Flume<dim>::sample() const
    {
      using Layout = PropertyLayout<dim>;
      // [-s_front, s_tail] for one min(), then sum |v|, sum v_x, sum v_y.
      double      extremes[2] = {std::numeric_limits<double>::max(),
                                 std::numeric_limits<double>::max()};
      double      sums[3]     = {0, 0, 0};
      const auto &grid        = this->get_grid();
      for (const auto &point : this->get_particle_handler())
        {
          const Point<dim>     x = grid.to_scene_frame(point.get_location());
          const Tensor<1, dim> v = grid.to_scene_frame(
            read_vector<dim>(&point.get_properties()[Layout::velocity]));
          const double s = bed_coordinates(x[0], x[1]).first;
          extremes[0]    = std::min(extremes[0], -s);
          extremes[1]    = std::min(extremes[1], s);
          sums[0] += v.norm();
          sums[1] += v[0];
          sums[2] += v[1];
        }
      const MPI_Comm comm = this->get_mpi_communicator();
      Utilities::MPI::min(ArrayView<const double>(extremes, 2),
                          comm,
                          ArrayView<double>(extremes, 2));
      Utilities::MPI::sum(ArrayView<const double>(sums, 3),
                          comm,
                          ArrayView<double>(sums, 3));
      const double n =
        std::max<double>(1, this->get_particle_handler().n_global_particles());
      Sample r;
      r.time             = this->get_time();
      r.s_front          = -extremes[0];
      r.s_tail           = extremes[1];
      r.x_front          = bed_point(r.s_front)[0];
      r.x_tail           = bed_point(r.s_tail)[0];
      r.mean_speed       = sums[0] / n;
      r.mean_velocity[0] = sums[1] / n;
      r.mean_velocity[1] = sums[2] / n;
      return r;
    }


    template <int dim>
    void
    Flume<dim>::initialize()
    {
      samples.push_back(sample());
      n_points_initial = this->get_particle_handler().n_global_particles();
    }


    template <int dim>
    void
    Flume<dim>::execute(const bool output_step)
    {
      // The front and tail only at output times; the mean speed, for its
      // peak and the stop time, at every step.
      Sample s;
      if (output_step)
      {
        s = sample();
        samples.push_back(s);
      }
      else
      {
        using Layout = PropertyLayout<dim>;
        double sum   = 0;
        for (const auto &point : this->get_particle_handler())
          sum +=
            read_vector<dim>(&point.get_properties()[Layout::velocity]).norm();
        s.time = this->get_time();
        s.mean_speed =
          Utilities::MPI::sum(sum, this->get_mpi_communicator()) /
          std::max<double>(1,
                           this->get_particle_handler().n_global_particles());
      }
      if (s.mean_speed > peak_speed)
      {
        peak_speed = s.mean_speed;
        peak_time  = s.time;
      }
      if (s.mean_speed >= stop_speed)
      {
        last_time_above_stop = s.time;
        first_time_after     = -1;
      }
      else if (first_time_after < 0)
        first_time_after = s.time;
      end_speed = s.mean_speed;
    }


    template <int dim>
    void
    Flume<dim>::write_report(std::ostream &report)
    {
      using Layout        = PropertyLayout<dim>;
      const auto    &grid = this->get_grid();
      const MPI_Comm comm = this->get_mpi_communicator();

      report
        << "## flume: incline " << theta * 180 / M_PI << " deg, arc radius "
        << radius << " m, break in slope at (" << break_point[0] << ", "
        << break_point[1]
        << "); s = distance along the bed from the arc's midpoint "
           "(negative upslope), x of the bed point at s\n"
        << "# time (s)   s_front (m)   s_tail (m)   x_front (m)   "
           "x_tail (m)   mean |v| (m/s)   mean v_x (m/s)   mean v_y (m/s)\n";
      const auto n_points = this->get_particle_handler().n_global_particles();
      for (const auto &s : samples)
        report << std::setw(10) << s.time << std::setw(14) << s.s_front
               << std::setw(14) << s.s_tail << std::setw(14) << s.x_front
               << std::setw(14) << s.x_tail << std::setw(14) << s.mean_speed
               << std::setw(14) << s.mean_velocity[0] << std::setw(14)
               << s.mean_velocity[1] << '\n';
      report << "material points: " << n_points_initial << " at the start, "
             << n_points << " at the end (" << n_points_initial - n_points
             << " left the mesh and were removed)\n";
      report << "peak mean speed (every step): " << peak_speed
             << " m/s at t = " << peak_time << " s\n";
      if (end_speed >= stop_speed)
        report << "mean speed still >= " << stop_speed << " m/s at the end ("
               << end_speed << " m/s)\n";
      else if (last_time_above_stop < 0)
        report << "mean speed below " << stop_speed << " m/s at every step\n";
      else
        report << "mean speed below " << stop_speed
               << " m/s from t = " << first_time_after << " s on (at the end "
               << end_speed << " m/s)\n";
      // The last output times within the tolerance of the final front.
      std::size_t rest = samples.size() - 1;
      while (rest > 0 && std::abs(samples[rest - 1].s_front -
                                  samples.back().s_front) <= front_tolerance)
        --rest;
      report << "front within " << front_tolerance
             << " m of its final position from t = " << samples[rest].time
             << " s on (output times)\n"
             << "final front: s = " << samples.back().s_front
             << " m, x = " << samples.back().x_front
             << " m; final tail: s = " << samples.back().s_tail
             << " m, x = " << samples.back().x_tail << " m\n";

      // Final deposit profile: bins of s between the tail and the front.
      const long first_bin = std::floor(samples.back().s_tail / bin_width);
      const long n_bins =
        std::floor(samples.back().s_front / bin_width) - first_bin + 1;
      // Per bin: volume, number of points; largest height separately.
      std::vector<double> sums(2 * n_bins, 0.), heights(n_bins, 0.);
      for (const auto &point : this->get_particle_handler())
        {
          const Point<dim> x = grid.to_scene_frame(point.get_location());
          const auto [s, h]  = bed_coordinates(x[0], x[1]);
          const long b = std::clamp<long>(std::floor(s / bin_width) - first_bin,
                                          0,
                                          n_bins - 1);
          sums[2 * b] += point.get_properties()[Layout::volume];
          sums[2 * b + 1] += 1;
          heights[b] = std::max(heights[b], h);
        }
      Utilities::MPI::sum(sums, comm, sums);
      Utilities::MPI::max(heights, comm, heights);
      report << "## flume: final deposit, bins of " << bin_width
             << " m along the bed; mean thickness = point volume per unit "
                "width / bin width; max height = largest normal distance of "
                "a point centre from the bed\n"
             << "# s centre (m)   x bed (m)   y bed (m)   mean thickness (m)   "
                "max height (m)   points\n";
      long thickest = -1;
      for (long b = 0; b < n_bins; ++b)
      {
        if (sums[2 * b + 1] == 0)
          continue;
        const double   s = (first_bin + b + 0.5) * bin_width;
        const Point<2> q = bed_point(s);
        report << std::setw(10) << s << std::setw(14) << q[0] << std::setw(14)
               << q[1] << std::setw(14) << sums[2 * b] / bin_width
               << std::setw(14) << heights[b] << std::setw(8) << sums[2 * b + 1]
               << '\n';
        if (thickest < 0 || sums[2 * b] > sums[2 * thickest])
          thickest = b;
      }
      if (thickest >= 0)
      {
        const double s = (first_bin + thickest + 0.5) * bin_width;
        report << "thickest deposit: mean thickness "
               << sums[2 * thickest] / bin_width << " m (max height "
               << heights[thickest] << " m) at s = " << s
               << " m, x = " << bed_point(s)[0] << " m\n";
      }
      std::vector<double> volume_in_bin(n_bins);
      double              total = 0;
      for (long b = 0; b < n_bins; ++b)
        {
          volume_in_bin[b] = sums[2 * b];
          total += sums[2 * b];
        }
      for (const double q : volume_fractions)
        {
          const double s_q =
            volume_quantile_in_bins(volume_in_bin, total, q, first_bin) *
            bin_width;
          report << "deposit holding " << 100 * q
                 << " % of the point volume from its tail, s: " << s_q
                 << " m (x = " << bed_point(s_q)[0] << " m)\n";
        }
    }


    template class Flume<2>;
    template class Flume<3>;
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::Flume,
                           "flume",
                           "the USGS flume (Denlinger and Iverson 2001): front, speed and deposit along the bed.")
