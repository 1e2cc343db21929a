#include <deal.II/base/mpi.h>

#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The stresses the frictional walls take, node by node, as a basal
     * force plate and a pore-pressure sensor would read them (Iverson's
     * flume measures both at the bed): at every output time a file
     * wall_tractions_NNNNN.csv with each wall node's position, outward
     * normal, its share A of the wall, the effective normal stress the
     * Coulomb part took (with a 'Normal stress memory length', the
     * remembered one), the pore pressure on the wall, their sum, the
     * shear traction, the slip speed after the update and the contact
     * state. The stresses are the nodal forces over A: on a node whose
     * cells are partly filled they are the force over the whole share.
     *
     * Why: the bed's friction is computed at the nodes from the nodal
     * forces, not from the points' stresses; where the two differ (the
     * pore pressure's half-cell error at a wall, a layer one or two
     * cells thick) only the nodes show what the bed was given. The
     * report gives the last output's means over the nodes in contact.
     */
    template <int dim>
    class WallTractions
      : public PostprocessorWithState<dim, WallTractions<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &)
      {}

      void
      initialize() override
      {
        this->get_boundary_conditions().record_wall_tractions();
      }

      void
      load_state(std::istream &in) override
      {
        PostprocessorWithState<dim, WallTractions<dim>>::load_state(in);
        this->get_boundary_conditions().record_wall_tractions();
      }

      void
      execute(const bool output_step) override
      {
        if (!output_step)
          return;
        const auto &local = this->get_boundary_conditions().wall_tractions();
        // Per node: position, normal, A, sigma'_n, p, tau, slip speed,
        // in contact, stuck.
        constexpr unsigned int n_values = 2 * dim + 7;
        std::vector<double>    values;
        values.reserve(local.size() * n_values);
        for (const auto &t : local)
          {
            for (unsigned int d = 0; d < dim; ++d)
              values.push_back(t.location[d]);
            for (unsigned int d = 0; d < dim; ++d)
              values.push_back(t.normal[d]);
            const double A = t.area;
            values.push_back(A);
            values.push_back(A > 0 ? t.effective_normal_force / A : 0.);
            values.push_back(A > 0 ? t.pore_pressure_force / A : 0.);
            values.push_back(A > 0 ? t.tangential_force / A : 0.);
            values.push_back(t.slip_speed);
            values.push_back(t.in_contact ? 1. : 0.);
            values.push_back(t.stuck ? 1. : 0.);
          }
        const MPI_Comm comm = this->get_mpi_communicator();
        const std::vector<std::vector<double>> all =
          Utilities::MPI::gather(comm, values, 0);
        const unsigned int index = n_files++;
        if (Utilities::MPI::this_mpi_process(comm) != 0)
          return;
        // Sorted by position, so that the file does not depend on the
        // ranks or the order of the nodes.
        std::vector<std::array<double, n_values>> rows;
        for (const auto &rank_values : all)
          for (unsigned int i = 0; i + n_values <= rank_values.size();
               i += n_values)
            {
              std::array<double, n_values> row;
              std::copy(rank_values.begin() + i,
                        rank_values.begin() + i + n_values,
                        row.begin());
              rows.push_back(row);
            }
        std::sort(rows.begin(), rows.end(), [](const auto &a, const auto &b) {
          return std::lexicographical_compare(a.begin(),
                                              a.begin() + dim,
                                              b.begin(),
                                              b.begin() + dim);
        });
        std::ostringstream name;
        name << this->get_output_directory() << "wall_tractions_"
             << std::setw(5) << std::setfill('0') << index << ".csv";
        std::ofstream file(name.str());
        file << "# t = " << std::setprecision(10) << this->get_time()
             << " s; stresses in Pa (compression positive), the pore "
                "pressure the excess over still water's in a 'Submerged' "
                "scene (nan on a drained wall)\n";
        const char *axes[] = {"x", "y", "z"};
        for (unsigned int d = 0; d < dim; ++d)
          file << axes[d] << ',';
        for (unsigned int d = 0; d < dim; ++d)
          file << "n_" << axes[d] << ',';
        file << "area,effective_normal_stress,pore_pressure,normal_stress,"
                "shear_traction,slip_speed,in_contact,stuck\n";
        file << std::setprecision(8);
        last = {};
        for (const auto &row : rows)
          {
            for (unsigned int c = 0; c < 2 * dim + 3; ++c)
              file << row[c] << ',';
            const double sigma = row[2 * dim + 1];
            const double p     = row[2 * dim + 2];
            file << (std::isnan(p) ? sigma : sigma + p) << ',';
            file << row[2 * dim + 3] << ',' << row[2 * dim + 4] << ','
                 << row[2 * dim + 5] << ',' << row[2 * dim + 6] << '\n';
            if (row[2 * dim + 5] > 0)
              {
                const double A = row[2 * dim];
                last.area += A;
                last.effective += A * sigma;
                last.pressure += A * (std::isnan(p) ? 0. : p);
                last.shear += A * row[2 * dim + 3];
                last.slip += A * row[2 * dim + 4];
                ++last.nodes;
              }
          }
        last.time = this->get_time();
      }

      void
      write_report(std::ostream &report) override
      {
        report << "## wall tractions: " << n_files
               << " file(s) wall_tractions_NNNNN.csv; the last (t = "
               << last.time << " s), area-weighted over the "
               << last.nodes << " wall nodes in contact:\n";
        if (last.area <= 0)
          {
            report << "no wall node in contact\n";
            return;
          }
        const double A = last.area;
        report << "wetted area: " << A << '\n'
               << "mean effective normal stress (Pa): " << last.effective / A
               << '\n'
               << "mean pore pressure (Pa): " << last.pressure / A << '\n'
               << "mean shear traction (Pa): " << last.shear / A << '\n'
               << "shear / effective normal: "
               << (last.effective > 0 ? last.shear / last.effective : 0.)
               << '\n'
               << "mean slip speed (m/s): " << last.slip / A << '\n';
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & n_files & last.time & last.area & last.effective &
          last.pressure & last.shear & last.slip & last.nodes;
      }

    private:
      /// Files written so far (the next file's number).
      unsigned int n_files = 0;
      /// The last output's sums over the nodes in contact (A, A sigma'_n,
      /// A p, A tau, A slip speed) and their number.
      struct Sums
      {
        double       time = 0, area = 0, effective = 0, pressure = 0,
               shear = 0, slip = 0;
        unsigned int nodes = 0;
      } last;
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::WallTractions,
                           "wall tractions",
                           "the frictional walls' effective normal stress, pore pressure, shear traction and slip speed node by node at output times (wall_tractions_NNNNN.csv), as a basal force plate and pore-pressure sensor read them.")
