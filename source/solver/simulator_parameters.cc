// The Simulator's parameters: the two parsing passes (the name lists that
// decide which subsections exist, then every entry) and what the parsed
// choices imply for the points' property slots.

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/solver/simulator.h>

#include <sstream>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::declare_name_lists(ParameterHandler &prm)
  {
    declare_dimension(prm);
    MaterialLibrary::declare_name_list(prm);
    PointGenerator<dim>::declare_name_list(prm);
    BoundaryConditions<dim>::declare_name_list(prm);
  }


  template <int dim>
  typename Simulator<dim>::NameLists
  Simulator<dim>::read_name_lists(ParameterHandler &prm)
  {
    NameLists names;
    names.materials  = MaterialLibrary::read_name_list(prm);
    names.regions    = PointGenerator<dim>::read_name_list(prm);
    names.boundaries = BoundaryConditions<dim>::read_name_list(prm);
    return names;
  }


  template <int dim>
  void
  Simulator<dim>::declare_parameters(ParameterHandler &prm,
                                     const NameLists  &names)
  {
    declare_dimension(prm);
    BackgroundGrid<dim>::declare_parameters(prm);
    MaterialLibrary::declare_parameters(prm, names.materials);
    PoreWater<dim>::declare_parameters(prm);
    PointGenerator<dim>::declare_parameters(prm, names.regions);
    LostPoints<dim>::declare_parameters(prm);
    PointRelocation<dim>::declare_parameters(prm);
    BoundaryConditions<dim>::declare_parameters(prm, names.boundaries);
    SideWallFriction<dim>::declare_parameters(prm);
    TimeSteppingParameters<dim>::declare_parameters(prm);
    VelocityTransfer<dim>::declare_parameters(prm);
    ParticleGridWeights<dim>::declare_parameters(prm);
    OutputWriter<dim>::declare_parameters(prm);
    LoadBalancing<dim>::declare_parameters(prm);
    Checkpointing<dim>::declare_parameters(prm);
    StabilityMonitor<dim>::declare_parameters(prm);
    RestCriterion::declare_parameters(prm);
    prm.enter_subsection("Postprocess");
    prm.declare_entry("List of postprocessors",
                      "",
                      Patterns::MultipleSelection(Postprocessors::names<dim>()),
                      "Comparisons with references that are run during the "
                      "simulation and written to report.txt in the output "
                      "directory: " +
                        PostprocessorRegistry<dim>::descriptions());
    prm.leave_subsection();
    Postprocessors::declare_parameters<dim>(prm);
  }


  template <int dim>
  void
  Simulator<dim>::parse_parameters(ParameterHandler  &prm,
                                   const std::string &input_dir)
  {
    input_directory = input_dir;
    std::ostringstream all_parameters;
    prm.print_parameters(all_parameters, ParameterHandler::ShortPRM);
    parameters_text = all_parameters.str();
    grid.parse_parameters(prm, input_directory);
    materials.parse_parameters(prm);
    pore_water.parse_parameters(prm);
    point_generator.parse_parameters(prm, materials, input_directory);
    lost_points.parse_parameters(prm);
    point_relocation.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm);
    side_walls.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    transfer.parse_parameters(prm);
    transfer.scheme().add_nodal_fields(nodal);
    weights = ParticleGridWeights<dim>::create(prm, *this);
    if (transfer.scheme().carries_affine_velocity() &&
        !time_stepping.step_scheme->updates_stress_from_remap() &&
        !weights->second_moment_bounded_below())
      pcout << "Warning: 'Transfer/Scheme = apic' with 'Time stepping/Update "
               "scheme' USF or USL fits each point's affine matrix to the "
               "end-of-step grid velocity, which on bilinear cells was "
               "measured unstable above CFL 0.05 (doc/transfers.md); MUSL "
               "takes it from the MUSL remap and is stable, and so are CPDI "
               "weights ('Transfer/Particle-grid weights = cpdi').\n";
    output_writer.parse_parameters(prm);
    load_balancing.parse_parameters(prm);
    stability_monitor.parse_parameters(prm);
    rest_criterion.parse_parameters(prm);
    checkpointing.parse_parameters(prm, output_writer.directory());
    prm.enter_subsection("Postprocess");
    postprocessor_names = split_name_list(prm.get("List of postprocessors"),
                                          "Postprocess/List of postprocessors");
    prm.leave_subsection();
    for (const auto &name : postprocessor_names)
      {
        postprocessors.push_back(Postprocessors::create<dim>(name, prm));
        postprocessors.back()->initialize_simulator(*this);
      }
  }


  template <int dim>
  std::vector<std::string>
  Simulator<dim>::state_variable_names() const
  {
    // Named by the model if there is one material, generically otherwise.
    const unsigned int       n_state = materials.max_n_state_variables();
    const auto               model_names = materials[0].model->state_variable_names();
    std::vector<std::string> names;
    for (unsigned int i = 0; i < n_state; ++i)
      names.push_back(materials.size() == 1 && i < model_names.size() ?
                        model_names[i] :
                        "state_" + std::to_string(i));
    return names;
  }


  // The members defined here (the class itself is instantiated in
  // simulator.cc): one explicit instantiation per member, so that
  // the Simulator's files can share one translation unit (unity
  // build) without instantiating the class twice.
#define MPM_INSTANTIATE(dim)                                                   \
  template void Simulator<dim>::declare_name_lists(ParameterHandler &);        \
  template typename Simulator<dim>::NameLists Simulator<dim>::read_name_lists( \
    ParameterHandler &);                                                       \
  template void Simulator<dim>::declare_parameters(ParameterHandler &,         \
                                                   const NameLists &);         \
  template void Simulator<dim>::parse_parameters(ParameterHandler &,           \
                                                 const std::string &);         \
  template std::vector<std::string> Simulator<dim>::state_variable_names()     \
    const;

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM
