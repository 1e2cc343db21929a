#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/column_collapse.h>
#include <mpm/postprocess/volume_quantiles.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    template <int dim>
    void
    ColumnCollapse<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Initial width",
                        "auto",
                        Patterns::Anything(),
                        "L0: width of the column at rest, in m, or 'auto': "
                        "the material's extent at the start, measured as "
                        "the front is (its farthest point plus half its "
                        "spacing from 'Wall position'). A number that "
                        "differs from that extent by more than 5 % is an "
                        "error: the runout, the aspect ratio and Lube's law "
                        "would be those of another column.");
      prm.declare_entry("Initial height",
                        "auto",
                        Patterns::Anything(),
                        "H0: height of the column at rest, in m, or 'auto' "
                        "(measured as 'Initial width' is, above 'Base "
                        "elevation'; the same check).");
      prm.declare_entry("Base elevation",
                        "0",
                        Patterns::Double(),
                        "y of the base, in m.");
      prm.declare_entry("Wall position",
                        "0",
                        Patterns::Double(),
                        "x of the wall the column leans on, in m; the "
                        "column flows towards +x.");
      prm.declare_entry("Stop speed",
                        "0.01",
                        Patterns::Double(0),
                        "The flow has stopped when the mean point speed "
                        "stays below this (m/s).");
      prm.declare_entry("Deposit bin width",
                        "0.005",
                        Patterns::Double(0),
                        "Width (m, along x) of the bins of the final deposit "
                        "profile in the report.");
      prm.declare_entry(
        "Front thickness",
        "0.01",
        Patterns::Double(0),
        "The report's second runout: where the final deposit's thickness "
        "(point volume per bin width, per unit width in 2D) falls below "
        "this (m), interpolated between bins. The front point (the first "
        "runout) is a single point's edge and moves with the resolution; "
        "this one measures the deposit (doc/column_collapse.md).");
      declare_volume_fractions(
        prm,
        "The report also gives, for each fraction q here, the runout within "
        "which the share q of the final point volume lies (from the wall "
        "outwards, interpolated in the bin where the sum crosses q). A "
        "cumulative measure: unlike the thickness threshold above, a thin "
        "tail whose thickness hovers near the threshold or a few thrown "
        "points do not move it by a bin or more (doc/column_collapse.md).");
    }


    template <int dim>
    void
    ColumnCollapse<dim>::parse_parameters(ParameterHandler &prm)
    {
      // A length in m, or 'auto' (0 here: measured in initialize()).
      const auto length = [&prm](const std::string &name) {
        const std::string value = Utilities::trim(prm.get(name));
        if (value == "auto")
          return 0.;
        double length = 0;
        try
          {
            length = Utilities::string_to_double(value);
          }
        catch (...)
          {
            length = -1;
          }
        if (!(length > 0))
          throw InputError("Postprocess/column collapse/" + name + " = '" +
                           value + "': must be 'auto' or a length > 0 (m).");
        return length;
      };
      given_width    = length("Initial width");
      given_height   = length("Initial height");
      base           = prm.get_double("Base elevation");
      wall           = prm.get_double("Wall position");
      stop_speed     = prm.get_double("Stop speed");
      bin_width       = prm.get_double("Deposit bin width");
      front_thickness = prm.get_double("Front thickness");
      volume_fractions = parse_volume_fractions(prm);
    }


    template <int dim>
    std::array<double, 3>
    ColumnCollapse<dim>::measure() const
    {
      using Layout = PropertyLayout<dim>;
      // The edge of the deposit: a point stands for a square of side
      // V_p^(1/dim) around it.
      std::array<double, 2> extremes{{-1e300, -1e300}};
      double                speed_sum = 0;
      for (const auto &point : this->get_particle_handler())
        {
          const auto   props = point.get_properties();
          const double half =
            0.5 * std::pow(props[Layout::volume], 1. / dim);
          const auto   x     = point.get_location();
          extremes[0]        = std::max(extremes[0], x[0] + half);
          extremes[1]        = std::max(extremes[1], x[dim - 1] + half);
          speed_sum += read_vector<dim>(&props[Layout::velocity]).norm();
        }
      const MPI_Comm comm = this->get_mpi_communicator();
      Utilities::MPI::max(ArrayView<const double>(extremes),
                          comm,
                          ArrayView<double>(extremes));
      const double n = this->get_particle_handler().n_global_particles();
      return {{extremes[0] - wall,
               extremes[1] - base,
               Utilities::MPI::sum(speed_sum, comm) / std::max(n, 1.)}};
    }


    template <int dim>
    void
    ColumnCollapse<dim>::initialize()
    {
      // The first line of the table: the column's extent at the start,
      // measured as the front and the height are later.
      execute(true);
      // L0 and H0: given ones must be the column's.
      const auto take = [](const double given,
                           const double measured,
                           const std::string &name) {
        if (given > 0 && std::abs(given - measured) > 0.05 * given)
          throw InputError(
            "Postprocess/column collapse/" + name + " = " +
            std::to_string(given) + " m, but the material's " +
            (name == "Initial width" ? "width" : "height") +
            " at the start is " + std::to_string(measured) +
            " m (its farthest point plus half its spacing from the wall or "
            "base): set the column's " +
            (name == "Initial width" ? "width" : "height") +
            ", or 'auto' to measure it.");
        return given > 0 ? given : measured;
      };
      width          = take(given_width, front, "Initial width");
      initial_height = take(given_height, height, "Initial height");
      double volume = 0;
      for (const auto &point : this->get_particle_handler())
        volume += point.get_properties()[PropertyLayout<dim>::volume];
      initial_volume =
        Utilities::MPI::sum(volume, this->get_mpi_communicator());
    }


    template <int dim>
    void
    ColumnCollapse<dim>::execute(const bool output_step)
    {
      // The mean speed at every step (for the stop time), the front and
      // height at output times only.
      const auto m = measure();
      mean_speed   = m[2];
      if (mean_speed >= stop_speed)
        last_time_above_stop = this->get_time();
      front  = m[0];
      height = m[1];
      if (output_step)
        {
          std::ostringstream line;
          line << std::setw(10) << this->get_time() << std::setw(14) << front
               << std::setw(14) << height << std::setw(14) << mean_speed
               << '\n';
          table += line.str();
        }
    }


    template <int dim>
    void
    ColumnCollapse<dim>::write_report(std::ostream &report)
    {
      const double a = initial_height / width;
      report << "## column collapse: L0 = " << width
             << " m, H0 = " << initial_height << " m, a = H0/L0 = " << a
             << "\n# time (s)  front L (m)  height H (m)  mean speed (m/s)\n"
             << table;
      report << "runout (L_inf - L0)/L0: " << (front - width) / width
             << "\nfinal height H_inf/L0: " << height / width
             << "\nfinal height H_inf/H0: " << height / initial_height
             << "\nmean speed at the end (m/s): " << mean_speed << '\n';
      if (mean_speed < stop_speed)
        report << "mean speed below " << stop_speed << " m/s from t = "
               << last_time_above_stop << " s on\n";
      else
        report << "still flowing at t = " << this->get_time()
               << " s: the runout is not final\n";
      // Lube et al. (2005) as commonly quoted (doc/column_collapse.md).
      report << "Lube et al. 2005 (as quoted): "
             << (a < 2.3 ? 1.2 * a : 1.9 * std::pow(a, 2. / 3.)) << '\n';

      // The final deposit: point volume per bin of x (collective).
      using Layout        = PropertyLayout<dim>;
      const long n_bins   = std::max(1L, std::lround((front - 0) / bin_width) + 1);
      std::vector<double> thickness(n_bins, 0.);
      for (const auto &point : this->get_particle_handler())
        {
          const long b = std::min(
            n_bins - 1,
            std::max(0L,
                     static_cast<long>((point.get_location()[0] - wall) /
                                       bin_width)));
          thickness[b] += point.get_properties()[Layout::volume] / bin_width;
        }
      // In 3D the column fills a channel of width W = V0 / (L0 H0) (slip
      // side walls): thickness is volume per bin width per channel width.
      const double channel_width =
        dim == 2 ? 1. : initial_volume / (width * initial_height);
      Utilities::MPI::sum(thickness, this->get_mpi_communicator(), thickness);
      double volume = 0;
      for (double &t : thickness)
        {
          volume += t * bin_width;
          t /= channel_width;
        }
      // The points' volume follows det(I + dt grad v): with a dilation
      // angle of 0 it should stay nearly constant; what it gained is
      // numerical bulking, which thickens the deposit.
      report << "total point volume at the end / at the start: "
             << volume / initial_volume << '\n';
      // The last bin at least front_thickness thick, and the crossing
      // towards the next one.
      long last = -1;
      for (long b = 0; b < n_bins; ++b)
        if (thickness[b] >= front_thickness)
          last = b;
      double deposit_front = 0;
      if (last >= 0)
        {
          deposit_front = (last + 0.5) * bin_width;
          if (last + 1 < n_bins)
            deposit_front += bin_width * (thickness[last] - front_thickness) /
                             (thickness[last] - thickness[last + 1]);
        }
      report << "runout of the deposit thicker than " << front_thickness
             << " m, (L - L0)/L0: " << (deposit_front - width) / width << '\n';
      // The connected deposit ends at the first empty bin: points thrown
      // ahead of the deposit, across a gap, do not count (the front point
      // above counts them). Known to the bin width.
      long first_empty = 0;
      while (first_empty < n_bins && thickness[first_empty] > 0)
        ++first_empty;
      report << "runout of the connected deposit (to the first empty bin of "
             << bin_width << " m), (L - L0)/L0: "
             << (first_empty * bin_width - width) / width << '\n';
      // Volume quantiles, in the unit of thickness (divided by the channel
      // width above).
      const double        total = volume / channel_width;
      std::vector<double> volume_in_bin(n_bins);
      for (long b = 0; b < n_bins; ++b)
        volume_in_bin[b] = thickness[b] * bin_width;
      for (const double q : volume_fractions)
        {
          const double x_q =
            volume_quantile_in_bins(volume_in_bin, total, q) * bin_width;
          report << "runout holding " << 100 * q
                 << " % of the point volume, (L - L0)/L0: "
                 << (x_q - width) / width << '\n';
        }
      report << "## column collapse: final deposit, bins of " << bin_width
             << " m in x; thickness = point volume per bin width"
             << (dim == 2 ? " (per unit width)" : " and channel width")
             << "\n# x centre (m)  thickness (m)\n";
      for (long b = 0; b < n_bins; ++b)
        report << std::setw(12) << (b + 0.5) * bin_width << std::setw(14)
               << thickness[b] << '\n';
    }


    template class ColumnCollapse<2>;
    template class ColumnCollapse<3>;
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::ColumnCollapse,
                           "column collapse",
                           "a granular column collapse on a rough base: runout and final height against the aspect ratio.")
