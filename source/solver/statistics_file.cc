#include <mpm/solver/statistics_file.h>

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace MPM
{
  template <int dim>
  std::vector<typename StatisticsFile<dim>::Column>
  StatisticsFile<dim>::columns() const
  {
    const auto scalar = [](auto value) {
      return [value](std::ostream &out, const Row &row) {
        out << ' ' << value(row);
      };
    };
    const auto vector = [](auto value) {
      return [value](std::ostream &out, const Row &row) {
        const Tensor<1, dim> v = value(row);
        for (unsigned int d = 0; d < dim; ++d)
          out << ' ' << v[d];
      };
    };
    std::vector<Column> list = {
      {"time", "s", 1, scalar([](const Row &r) { return r.statistics.time; })},
      {"step", "", 1, scalar([](const Row &r) { return r.statistics.step; })},
      {"time step",
       "s",
       1,
       scalar([](const Row &r) { return r.statistics.time_step; })},
      {"points",
       "",
       1,
       scalar([](const Row &r) { return r.statistics.n_points; })},
      {"mass", "kg", 1, scalar([](const Row &r) { return r.statistics.mass; })},
      {"momentum",
       "kg m/s",
       dim,
       vector([](const Row &r) { return r.statistics.momentum; })},
      {"kinetic energy",
       "J",
       1,
       scalar([](const Row &r) { return r.statistics.kinetic_energy; })},
      {"strain energy",
       "J",
       1,
       scalar([](const Row &r) { return r.statistics.strain_energy; })},
      {"gravitational potential energy",
       "J",
       1,
       scalar([](const Row &r) {
         return r.statistics.gravitational_potential_energy;
       })},
      {"mean speed",
       "m/s",
       1,
       scalar([](const Row &r) { return r.statistics.mean_speed; })},
      {"centre of mass",
       "m",
       dim,
       vector([](const Row &r) {
         // Zero origin: the sum is left out, which would turn -0 into 0.
         if (r.local_origin.norm() > 0)
           return Tensor<1, dim>(r.statistics.centre_of_mass) + r.local_origin;
         return Tensor<1, dim>(r.statistics.centre_of_mass);
       })},
      {"removed points",
       "",
       1,
       scalar([](const Row &r) { return r.removed_points; })},
      {"removed mass",
       "kg",
       1,
       scalar([](const Row &r) { return r.removed_mass; })}};
    if (with_pore_water)
      list.insert(
        list.end(),
        {{"water mass",
          "kg",
          1,
          scalar([](const Row &r) { return r.statistics.water_mass; })},
         {"water momentum",
          "kg m/s",
          dim,
          vector([](const Row &r) { return r.statistics.water_momentum; })},
         {"mean pore pressure",
          "Pa",
          1,
          scalar(
            [](const Row &r) { return r.statistics.mean_pore_pressure; })}});
    return list;
  }


  template <int dim>
  void
  StatisticsFile<dim>::open(const std::string  &name,
                            const bool          resume,
                            const std::uint64_t resume_length,
                            const bool          with_water)
  {
    with_pore_water = with_water;
    if (resume)
      {
        if (std::filesystem::exists(name) &&
            std::filesystem::file_size(name) > resume_length)
          std::filesystem::resize_file(name, resume_length);
        file.open(name, std::ios::app);
        return;
      }
    file.open(name);
    file << "# Columns: ";
    unsigned int first = 1;
    bool         comma = false;
    for (const auto &column : columns())
      {
        file << (comma ? ", " : "") << first;
        if (column.n_components > 1)
          file << '-' << first + column.n_components - 1;
        file << ' ' << column.name;
        if (!column.unit.empty())
          file << " (" << column.unit << ')';
        first += column.n_components;
        comma = true;
      }
    file << (dim == 2 ? ". Mass, momentum, energies and removed mass per "
                        "unit thickness (2D); mean speed not mass-weighted.\n" :
                        ". Mean speed not mass-weighted.\n");
  }


  template <int dim>
  std::uint64_t
  StatisticsFile<dim>::length() const
  {
    return file.is_open() ? static_cast<std::uint64_t>(file.tellp()) : 0;
  }


  template <int dim>
  void
  StatisticsFile<dim>::write_row(const Row &row)
  {
    if (!file.is_open())
      return;
    // The first column without the leading space of the others.
    std::ostringstream line;
    line << std::setprecision(10);
    for (const auto &column : columns())
      column.write(line, row);
    file << line.str().substr(1) << '\n';
    file.flush();
  }


  template class StatisticsFile<2>;
  template class StatisticsFile<3>;
} // namespace MPM
