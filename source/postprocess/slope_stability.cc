#include <deal.II/base/mpi.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <boost/serialization/utility.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * A slope from stability to runout (doc/slope_stability.md). The
     * material points nearest to the slope's crest and toe at the start are
     * followed; every 'Record interval' the report gets a row with the
     * strength reduction factor F in force ('Materials/Strength reduction
     * factor'), the displacement of both points and the kinetic energy.
     *
     * Failure criterion. Explicit MPM has no equivalent of the
     * non-convergence of an implicit finite element solution (Griffiths
     * and Lane 1999): a slope with too little strength does not stop the
     * run, it moves, and with local damping ('Time stepping/Local
     * damping') a statically admissible slope comes to rest. So the slope
     * counts as failed if the crest point has not come to rest by the end
     * of the run: its mean speed over the last 'Rest check interval' is
     * above 'Rest speed' (the explicit counterpart of an iteration limit
     * and a tolerance). With a constant F, scripts/strength_reduction.sh
     * bisects F on this answer; doc/slope_stability.md shows the crest
     * displacement against F, and how the factor moves with the
     * tolerances. For runs whose F changes with time the report also gives
     * the first time (and F) at which the crest displacement exceeded
     * 'Failure displacement'.
     *
     * At the end the report gives the ground surface (the top of the
     * points, in bins of x), the front (how far the material has run
     * beyond the toe, where the surface stands 'Front thickness' above the
     * toe's level) and the scarp (how far behind the crest the surface has
     * dropped by more than 'Scarp drop'): a single slide leaves the scarp
     * near the crest, a retrogressive failure moves it back.
     *
     * 2D, or 3D with x along the slope and z up (bins in x over the whole
     * width).
     */
    template <int dim>
    class SlopeStability : public PostprocessorWithState<dim, SlopeStability<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Crest",
                          dim == 2 ? "20, 10" : "20, 0, 10",
                          Patterns::Anything(),
                          "The slope's crest (m): the material point nearest "
                          "to it at the start is followed.");
        prm.declare_entry("Toe",
                          dim == 2 ? "0, 0" : "0, 0, 0",
                          Patterns::Anything(),
                          "The slope's toe (m): the material point nearest to "
                          "it at the start is followed. The slope runs out "
                          "from the crest towards the toe along x.");
        prm.declare_entry("Record interval",
                          "0.1",
                          Patterns::Double(0),
                          "Time between the rows of the report (s); the "
                          "failure check is made at these times.");
        prm.declare_entry("Rest check interval",
                          "2",
                          Patterns::Double(0),
                          "The slope has failed if the crest point's mean "
                          "speed over this last part of the run (s) is above "
                          "'Rest speed'. A multiple of 'Record interval'.");
        prm.declare_entry("Rest speed",
                          "1e-4",
                          Patterns::Double(0),
                          "See 'Rest check interval' (m/s).");
        prm.declare_entry("Failure displacement",
                          "0.5",
                          Patterns::Double(0),
                          "The report gives the first time and the strength "
                          "reduction factor at which the crest point has "
                          "moved by more than this (m).");
        prm.declare_entry("Profile bin width",
                          "0.5",
                          Patterns::Double(0),
                          "Width (m, along x) of the bins of the final ground "
                          "surface in the report.");
        prm.declare_entry("Front thickness",
                          "0.1",
                          Patterns::Double(0),
                          "The front is the last bin, counted from the crest "
                          "towards and past the toe, whose surface stands "
                          "more than this (m) above the toe.");
        prm.declare_entry("Scarp drop",
                          "0.1",
                          Patterns::Double(0),
                          "The scarp is the bin farthest behind the crest "
                          "whose surface has dropped by more than this (m) "
                          "below the crest's initial height.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        const std::string path = "Postprocess/slope stability/";
        crest = parse_point<dim>(prm.get("Crest"), path + "Crest");
        toe   = parse_point<dim>(prm.get("Toe"), path + "Toe");
        record_interval      = prm.get_double("Record interval");
        failure_displacement = prm.get_double("Failure displacement");
        rest_interval        = prm.get_double("Rest check interval");
        rest_speed           = prm.get_double("Rest speed");
        bin_width            = prm.get_double("Profile bin width");
        front_thickness      = prm.get_double("Front thickness");
        scarp_drop           = prm.get_double("Scarp drop");
        check_input(crest[dim - 1] > toe[dim - 1] && crest[0] != toe[0],
                    path + "Crest must lie above the toe and beside it in x "
                           "(crest " +
                      prm.get("Crest") + ", toe " + prm.get("Toe") + ").");
        check_input(record_interval > 0 && bin_width > 0 &&
                      failure_displacement > 0 && rest_interval > 0,
                    path + "Record interval, Rest check interval, Failure "
                           "displacement and Profile bin width must be > 0.");
      }

      void
      initialize() override
      {
        // The nearest point to each of crest and toe, over all ranks.
        const std::array<Point<dim>, 2> targets{{crest, toe}};
        for (unsigned int k = 0; k < 2; ++k)
          {
            double                      best = std::numeric_limits<double>::max();
            types::particle_index       id   = 0;
            Point<dim>                  x;
            for (const auto &point : this->get_particle_handler())
              {
                const double d = point.get_location().distance(targets[k]);
                if (d < best)
                  {
                    best = d;
                    id   = point.get_id();
                    x    = point.get_location();
                  }
              }
            std::vector<double> mine{best, static_cast<double>(id)};
            for (unsigned int d = 0; d < dim; ++d)
              mine.push_back(x[d]);
            const auto all =
              Utilities::MPI::all_gather(this->get_mpi_communicator(), mine);
            const auto nearest = std::min_element(
              all.begin(), all.end(), [](const auto &a, const auto &b) {
                return a[0] < b[0];
              });
            check_input((*nearest)[0] < std::numeric_limits<double>::max(),
                        "Postprocess/slope stability: there are no material "
                        "points to follow.");
            ids[k] = static_cast<types::particle_index>((*nearest)[1]);
            for (unsigned int d = 0; d < dim; ++d)
              initial[k][d] = (*nearest)[2 + d];
          }
        record();
        next_record = record_interval;
      }

      void
      execute(const bool) override
      {
        if (this->get_time() >= next_record * (1 - 1e-12))
          {
            record();
            next_record =
              record_interval *
              (std::floor(this->get_time() / record_interval + 1e-9) + 1);
          }
      }

      void
      write_report(std::ostream &report) override
      {
        if (this->get_time() > last_record_time)
          record();
        const double height = crest[dim - 1] - toe[dim - 1];
        const double sense  = crest[0] > toe[0] ? -1. : 1.;
        report << "## slope stability: toe (" << toe << "), crest (" << crest
               << "), height " << height << " m; followed points: crest ("
               << initial[0] << "), toe (" << initial[1] << ")\n"
               << "# time (s)  strength reduction F  crest displacement (m)  "
                  "toe displacement (m)  kinetic energy (J)\n"
               << table;
        // The crest's mean speed over the last rest_interval: from the
        // last record at least that long before the end.
        const double now    = this->get_time();
        std::size_t  before = 0;
        for (std::size_t i = 0; i < crest_history.size(); ++i)
          if (crest_history[i].first <= now - rest_interval * (1 - 1e-9))
            before = i;
        const double span = now - crest_history[before].first;
        const double speed =
          span > 0 ? crest_history.back().second.distance(
                       crest_history[before].second) /
                       span :
                     std::numeric_limits<double>::quiet_NaN();
        if (!(speed <= rest_speed))
          report << "slope failed: the crest point moves at " << speed
                 << " m/s over the last " << span << " s (rest speed "
                 << rest_speed << " m/s), F = " << last_factor << '\n';
        else
          report << "slope stable: the crest point moves at " << speed
                 << " m/s over the last " << span << " s (rest speed "
                 << rest_speed << " m/s), F = " << last_factor << '\n';
        report << "crest displacement at the end (m): "
               << last_crest_displacement << '\n';
        if (passed_displacement)
          report << "crest displacement above " << failure_displacement
                 << " m from t = " << passing_time << " s, F = "
                 << passing_factor << '\n';

        // The ground surface: the top of the points per bin of x.
        double x_min = std::numeric_limits<double>::max(), x_max = -x_min;
        for (const auto &point : this->get_particle_handler())
          {
            x_min = std::min(x_min, point.get_location()[0]);
            x_max = std::max(x_max, point.get_location()[0]);
          }
        const MPI_Comm comm = this->get_mpi_communicator();
        x_min               = Utilities::MPI::min(x_min, comm);
        x_max               = Utilities::MPI::max(x_max, comm);
        const double start  = bin_width * std::floor(x_min / bin_width);
        const long   n_bins =
          std::max(1L, static_cast<long>(std::ceil((x_max - start) / bin_width)));
        std::vector<double> surface(n_bins, -std::numeric_limits<double>::max());
        for (const auto &point : this->get_particle_handler())
          {
            const double half =
              0.5 * std::pow(point.get_properties()[PropertyLayout<dim>::volume],
                             1. / dim);
            const long b = std::min(
              n_bins - 1,
              std::max(0L,
                       static_cast<long>((point.get_location()[0] - start) /
                                         bin_width)));
            surface[b] =
              std::max(surface[b], point.get_location()[dim - 1] + half);
          }
        Utilities::MPI::max(surface, comm, surface);
        // Front: the farthest bin in the runout sense (from the toe on)
        // standing front_thickness above the toe. Scarp: the bin farthest
        // behind the crest that has dropped by scarp_drop.
        double front = 0, scarp = 0;
        for (long b = 0; b < n_bins; ++b)
          {
            if (surface[b] == -std::numeric_limits<double>::max())
              continue;
            const double x          = start + (b + 0.5) * bin_width;
            const double beyond_toe = sense * (x - toe[0]);
            if (surface[b] > toe[dim - 1] + front_thickness)
              front = std::max(front, beyond_toe);
            const double behind_crest = -sense * (x - crest[0]);
            if (behind_crest > 0 && surface[b] < crest[dim - 1] - scarp_drop)
              scarp = std::max(scarp, behind_crest);
          }
        report << "front beyond the toe (m): " << front << "  (/ H: "
               << front / height << ")\n"
               << "scarp behind the crest (m): " << scarp << "  (/ H: "
               << scarp / height << ")\n"
               << "## slope stability: final ground surface, bins of "
               << bin_width << " m in x\n# x centre (m)  surface (m)\n";
        for (long b = 0; b < n_bins; ++b)
          if (surface[b] != -std::numeric_limits<double>::max())
            report << std::setw(10) << start + (b + 0.5) * bin_width
                   << std::setw(14) << surface[b] << '\n';
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &ids[0] &ids[1] &initial[0] &initial[1] &table &next_record
          &last_record_time &crest_history &passed_displacement
            &passing_time &passing_factor &last_crest_displacement
              &last_factor;
      }

    private:
      /// A row of the table at the current time (collective).
      void
      record()
      {
        using Layout = PropertyLayout<dim>;
        // Kinetic energy, then the two points' positions and whether this
        // rank has them.
        std::vector<double> sums(1 + 2 * (dim + 1), 0.);
        for (const auto &point : this->get_particle_handler())
          {
            const auto props = point.get_properties();
            sums[0] += 0.5 * props[Layout::mass] *
                       read_vector<dim>(&props[Layout::velocity]).norm_square();
            for (unsigned int k = 0; k < 2; ++k)
              if (point.get_id() == ids[k])
                {
                  for (unsigned int d = 0; d < dim; ++d)
                    sums[1 + k * (dim + 1) + d] = point.get_location()[d];
                  sums[1 + k * (dim + 1) + dim] = 1;
                }
          }
        Utilities::MPI::sum(sums, this->get_mpi_communicator(), sums);
        std::array<double, 2> displacement{};
        for (unsigned int k = 0; k < 2; ++k)
          {
            // A followed point that left the mesh is reported as lost by
            // the simulator; here its displacement is unknown.
            if (sums[1 + k * (dim + 1) + dim] != 1)
              {
                displacement[k] = std::numeric_limits<double>::quiet_NaN();
                continue;
              }
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = sums[1 + k * (dim + 1) + d];
            displacement[k] = x.distance(initial[k]);
          }
        const double factor = this->get_materials().strength_reduction_factor();
        std::ostringstream row;
        row << std::setw(10) << this->get_time() << std::setw(12) << factor
            << std::setw(16) << displacement[0] << std::setw(16)
            << displacement[1] << std::setw(16) << sums[0] << '\n';
        table += row.str();
        last_record_time          = this->get_time();
        last_crest_displacement = displacement[0];
        last_factor             = factor;
        Point<dim> crest_position = initial[0];
        if (sums[1 + dim] == 1)
          for (unsigned int d = 0; d < dim; ++d)
            crest_position[d] = sums[1 + d];
        else
          for (unsigned int d = 0; d < dim; ++d)
            crest_position[d] = std::numeric_limits<double>::quiet_NaN();
        crest_history.emplace_back(this->get_time(), crest_position);
        if (!passed_displacement && !(displacement[0] <= failure_displacement))
          {
            passed_displacement = true;
            passing_time        = this->get_time();
            passing_factor      = factor;
          }
      }

      Point<dim>             crest, toe;
      double                 record_interval      = 0.1;
      double                 failure_displacement = 0.5;
      double                 bin_width            = 0.5;
      double                 front_thickness      = 0.1;
      double                 scarp_drop           = 0.1;
      std::array<types::particle_index, 2> ids{};
      std::array<Point<dim>, 2>            initial;
      std::string                          table;
      double                               next_record      = 0;
      double                               last_record_time = -1;
      double                               rest_interval    = 2;
      double                               rest_speed       = 1e-4;
      /// (time, crest point position) of every record.
      std::vector<std::pair<double, Point<dim>>> crest_history;
      bool                                 passed_displacement = false;
      double                               passing_time        = 0;
      double                               passing_factor      = 0;
      double                               last_crest_displacement = 0;
      double                               last_factor             = 1;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::SlopeStability,
                           "slope stability",
                           "a slope's crest and toe displacement against the strength reduction factor, its failure, and its runout and scarp.")
