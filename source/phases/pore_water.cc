#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>

#include <mpm/base/function_input.h>
#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/phases/pore_water.h>

#include <algorithm>
#include <cmath>

namespace MPM
{
  template <int dim>
  void
  PoreWater<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Pore water");
    prm.declare_entry("Density",
                      "1000",
                      Patterns::Double(0),
                      "Density rho_w of the pore water in kg/m^3 (materials "
                      "with 'Porosity' > 0; doc/pore_water.md).");
    prm.declare_entry("Bulk modulus",
                      "2.2e9",
                      Patterns::Double(0),
                      "Bulk modulus K_w of the pore water in Pa: the pore "
                      "pressure rises by K_w / n times the volume of water "
                      "a point gains per volume of pores. It sets the time "
                      "step through the two phases' fast P wave, a little "
                      "faster than the undrained sqrt((M + K_w / n) / rho) "
                      "(doc/pore_water.md, 'The formulation').");
    prm.declare_entry("Viscosity",
                      "1e-3",
                      Patterns::Double(0),
                      "Dynamic viscosity mu of the pore water in Pa s; the "
                      "drag per volume is n^2 mu / k (v_w - v_s).");
    prm.declare_entry("Permeability law",
                      "constant",
                      Patterns::Selection("constant|kozeny-carman"),
                      "How a point's permeability follows its porosity n: "
                      "'constant', the material's 'Permeability' k0; "
                      "'kozeny-carman', k0 (n^3 / (1 - n)^2) / (n0^3 / "
                      "(1 - n0)^2) with n0 the material's 'Porosity' (a "
                      "compacting skeleton drains more slowly, a dilating "
                      "one faster).");
    prm.declare_entry("Initial pore pressure",
                      "0",
                      Patterns::Anything(),
                      "Pore pressure p in Pa (compression positive) of the "
                      "points of saturated materials at the start, a "
                      "function of the scene's coordinates x, y (and z), "
                      "e.g. '1000 * 9.81 * (2 - y)' under a water table at "
                      "y = 2 m. The materials' 'Initial stress' is their "
                      "effective stress.");
    prm.declare_entry(
      "Submerged",
      "false",
      Patterns::Bool(),
      "Whether the scene lies in still water whose surface is above every "
      "material (a column in a tank, a lake's bed; every material must "
      "then be saturated). The points' pore pressure is then the excess "
      "over the still water's hydrostatic pressure: the water's own weight "
      "is balanced by that pressure and left out, the skeleton carries its "
      "buoyant weight (rho_d - (1 - n) rho_w) V g, and a free surface of "
      "the material is at the still water's pressure (excess 0), as the "
      "weak form has it. 'Initial pore pressure', the boundaries' 'Pore "
      "pressure' and every reported pore pressure are excess pressures, "
      "and the geostatic stress is the buoyant weight. The still water's "
      "own flow and its drag on the material's surface are not modelled. "
      "false: the pore pressure is the total one and the water has its "
      "weight (a water table inside the material).");
    prm.declare_entry(
      "Water velocity transfer",
      "transfer scheme",
      Patterns::Selection("affine|transfer scheme"),
      "How the water's velocity goes between the points and the nodes. "
      "'transfer scheme': the skeleton's FLIP share (the blend's 'FLIP "
      "fraction'; PIC under APIC and XPIC). PIC loses the water's velocity "
      "variation over a cell at every step, so that a fast saturated flow "
      "depends on the time step (the saturated USGS flume's mean speed at "
      "0.1 s: 0.253 / 0.359 / 0.447 m/s with steps of 8.6e-6 / 4.2e-6 / "
      "1.1e-6 s). "
      "'affine' (experimental; with 'Transfer/Scheme = apic', other schemes "
      "take 'transfer scheme'): as the skeleton's APIC, each point carries "
      "an affine matrix C_w fitted to the water's nodal velocity (B D^-1 on "
      "CPDI weights, the gradient on linear ones) and hands the nodes "
      "v_w + C_w (x_i - x_p): the flume then depends little on the step "
      "(0.126 / 0.133 m/s with steps of 8.6e-6 / 4.2e-6 s); on a Coulomb "
      "bed it needs the wall's 'Normal stress memory length' (a saturated "
      "layer sliding on one stops at CFL 0.3 and above without it, is "
      "exact at CFL 0.5 with 1 mm: the friction's flutter, which PIC "
      "damps); doc/pore_water.md, 'A saturated flume: the time step'.");
    prm.declare_entry(
      "Pressure rate averaging",
      "patch",
      Patterns::Selection("none|cell|patch|node"),
      "The volumetric rate (1 - n) div v_s + n div v_w of the pore "
      "pressure's balance dp = -(K_w / n) rate dt, against the pressure "
      "oscillation of single-point MPM (doc/pore_water.md, 'Pressure "
      "stabilisation'). 'patch' (the default): the volume-weighted mean "
      "over the saturated points of each cell, averaged again over the "
      "patches of cells around the cell's vertices (each vertex the "
      "volume-weighted mean of the cells around it, each cell the mean of "
      "its vertices, as the skeleton's 'Volumetric strain averaging = "
      "patch'). 'cell': the cell's mean alone; the pressure's increments "
      "are then constant over a cell, and a pressure constant per cell has "
      "a checkerboard (cells alternating in sign) that its nodal forces do "
      "not feel, so nothing holds it back: in the submerged collapse on "
      "1.25 mm cells it grows to +-7 kPa within 0.3 s and a sheet of "
      "points runs ahead, where 'patch' keeps -17 / +201 Pa (the patch "
      "average of a checkerboard is zero). Both put a pressure gradient "
      "that grows inside the material (suction near a drained surface) in "
      "the jumps between cells (first order in h); on Terzaghi's layer "
      "they agree (largest error at T = 0.05 3.24 % of the load with "
      "'patch', 3.19 % with 'cell', 20 cells). 'node': the volume-weighted "
      "mean of the points' own rates at each node, interpolated back to "
      "the points: continuous, linear over a cell on linear weights, so "
      "that the pressure's slope within a cell follows the drainage "
      "(Terzaghi's layer on 20 cells: 0.63 %; steady seepage 4e-5 against "
      "4e-3), at the cost of a second pair of passes. For consolidation "
      "and seepage only: in a flow the points' pressures scatter by tens "
      "of kPa and the run fails (a saturated column collapse: a point "
      "thrown through the base at 0.44 s), as the forces take each "
      "point's own pressure and the rates the nodes' means. 'none': each "
      "point's own (in the saturated USGS flume a third of the points "
      "then lay beyond +-2 kPa where the hydrostatic pressure is below 1 "
      "kPa).");
    prm.declare_entry(
      "Pressure projection",
      "cell linear",
      Patterns::Selection("none|cell linear"),
      "'cell linear': after each step the pore pressures of the saturated "
      "points of each cell are replaced by their volume-weighted "
      "least-squares linear fit over the cell. A field linear over each "
      "cell is kept to round-off; what it removes is the point-to-point "
      "scatter that points sheared across cells carry in (in the saturated "
      "USGS flume with 'cell' averaging the 1st-99th percentiles at 0.4 s "
      "shrink from -3.4 ... +3.2 kPa to -0.6 ... +0.3 kPa and the run "
      "reaches rest instead of inverting a CPDI domain at 0.665 s; "
      "doc/pore_water.md, 'Pressure stabilisation'). Meant with "
      "'Pressure rate averaging = patch' or 'cell': with each point's own "
      "rate the cells' fits scatter instead. With 2 points per cell "
      "direction it "
      "removes little (a saturated collapse: -2.8 ... +2.6 kPa at rest "
      "against -0.7 ... +1.0 kPa with 3): run saturated flows with 3. "
      "'none': each point keeps its own.");
    prm.declare_entry(
      "Free surface volume fraction",
      "0.25",
      Patterns::Double(0, 1),
      "The saturated points of a cell whose volume fills less than this "
      "share of the cell lie at a free surface and are drained: their "
      "pore pressure is set to 0 after each step (the excess over the "
      "still water's with 'Submerged'). Without it a lone point at a "
      "flow's front, or a thin sheet of points, keeps the pressure its own "
      "volumetric rate gives it, and where its weights on some nodes are "
      "small the water's stiffness there is not bounded by the step's "
      "wave speed: its pressure alternates in sign and grows (the "
      "saturated USGS flume, affine water: a front point on the runout "
      "after its CPDI domain was reset next to the bed, -1 MPa within 12 "
      "steps, then thrown out of the mesh; doc/pore_water.md, 'A drained "
      "free surface'). 0: no point is drained this way (the weak form's "
      "natural condition p = 0 at a free surface alone).");
    prm.declare_entry(
      "Wall pore pressure",
      "water push",
      Patterns::Selection("water push|excess gradient"),
      "The pore pressure on an impermeable frictional wall, whose Coulomb "
      "friction takes the effective normal force (the mixture's reaction "
      "less p A). 'water push': the water's own push on the wall without "
      "the drag over the nodal porosity, exact where the pressure is "
      "hydrostatic; under an excess pore pressure that grows with depth it "
      "misses the excess gradient's weight over the half cell above the "
      "wall (a layer carrying 0.8 of its buoyant weight by excess pore "
      "pressure slides 15.9 / 31.9 % slow two / one cell thick). 'excess "
      "gradient': adds that weight, the pore pressure's gradient normal to "
      "the wall taken as its share r = p / (p - sigma'_nn) of the total "
      "normal stress's, r rho g.n, from the saturated points' averages at "
      "the node: the same layers slide within 2e-4 / 5e-4 of the closed "
      "form (with the wall's 'Normal stress memory length'), and a "
      "liquefied sheet one or two cells thick gets its pore pressure on "
      "the bed (doc/pore_water.md, 'Friction in effective stress'). It "
      "makes the friction depend on the effective stress at the wall: "
      "without the wall's 'Normal stress memory length' the flutter of "
      "Coulomb friction grows sooner (the one-cell layer from 0.07 s, "
      "then 25 % slow; with the water push from about 1.1 s).");
    prm.leave_subsection();
  }


  template <int dim>
  void
  PoreWater<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Pore water");
    water_density = prm.get_double("Density");
    bulk_modulus  = prm.get_double("Bulk modulus");
    viscosity     = prm.get_double("Viscosity");
    kozeny_carman = prm.get("Permeability law") == "kozeny-carman";
    const std::string averaging = prm.get("Pressure rate averaging");
    rate_averaging              = averaging == "node"  ? RateAveraging::node :
                                  averaging == "cell"  ? RateAveraging::cell :
                                  averaging == "patch" ? RateAveraging::patch :
                                                         RateAveraging::none;
    project_pressure      = prm.get("Pressure projection") == "cell linear";
    free_surface_fraction = prm.get_double("Free surface volume fraction");
    affine_requested      = prm.get("Water velocity transfer") == "affine";
    submerged             = prm.get_bool("Submerged");
    wall_excess_gradient  = prm.get("Wall pore pressure") == "excess gradient";
    check_input(water_density > 0 && bulk_modulus > 0 && viscosity > 0,
                "Pore water: Density (" + prm.get("Density") +
                  "), Bulk modulus (" + prm.get("Bulk modulus") +
                  ") and Viscosity (" + prm.get("Viscosity") +
                  ") must be > 0.");
    initial_pressure_expression = prm.get("Initial pore pressure");
    initial_pressure = std::make_unique<FunctionParser<dim>>(1);
    parse_function_or_throw("Pore water/Initial pore pressure = '" +
                              initial_pressure_expression + "'",
                            [&]() {
                              initial_pressure->initialize(
                                dim == 2 ? "x,y" : "x,y,z",
                                initial_pressure_expression,
                                {{"_pi", numbers::PI}, {"_e", numbers::E}});
                              initial_pressure->value(Point<dim>());
                            });
    prm.leave_subsection();
  }


  template <int dim>
  void
  PoreWater<dim>::initialize(const MaterialLibrary &materials,
                             NodalFields           &nodal)
  {
    material_porosity.clear();
    material_dry_density.clear();
    material_permeability.clear();
    is_active = false;
    for (unsigned int m = 0; m < materials.size(); ++m)
      {
        material_porosity.push_back(materials[m].porosity);
        material_dry_density.push_back(materials[m].density);
        material_permeability.push_back(materials[m].permeability);
        is_active = is_active || materials[m].porosity > 0;
      }
    if (submerged)
      for (unsigned int m = 0; m < materials.size(); ++m)
        check_input(materials[m].porosity > 0,
                    "Pore water/Submerged = true: material '" +
                      materials[m].name +
                      "' is dry ('Porosity' 0). In still water every "
                      "material must be saturated (a dry one's buoyancy "
                      "is not modelled).");
    if (!is_active)
      return;
    for (NodalVector *field : {&mass,
                               &momentum,
                               &force,
                               &skeleton_pressure_force,
                               &drag,
                               &volume_sums})
      nodal.add(*field, NodalFields::Ghosts::summed);
    if (wall_excess_gradient)
      for (NodalVector &field : wall_state_sums)
        nodal.add(field, NodalFields::Ghosts::summed);
    nodal.add(nodal_porosity, NodalFields::Ghosts::computed);
    nodal.add(velocity, NodalFields::Ghosts::computed);
    nodal.add(velocity_new, NodalFields::Ghosts::computed);
    nodal.add(velocity_against_held_skeleton, NodalFields::Ghosts::computed);
    if (rate_averaging == RateAveraging::node)
      nodal_rate.initialize(
        nodal,
        volume_sums,
        bulk_modulus,
        project_pressure || free_surface_fraction > 0 ?
          typename NodalPressureRate<dim>::CellFinish(
            [this](const ArrayView<double *const>    &props,
                   const ArrayView<const Point<dim>> &positions,
                   const double                       cell_volume) {
              finish_cell_pressures(props, positions, cell_volume);
            }) :
          typename NodalPressureRate<dim>::CellFinish());
  }


  template <int dim>
  std::vector<std::string>
  PoreWater<dim>::point_property_names() const
  {
    std::vector<std::string> names(dim, "water_velocity");
    names.push_back("pore_pressure");
    names.push_back("porosity");
    if (affine)
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          names.push_back(std::string("water_affine_") + "xyz"[a] + "xyz"[b]);
    if (rate_averaging == RateAveraging::node)
      names.push_back("volumetric_rate");
    return names;
  }


  template <int dim>
  void
  PoreWater<dim>::initialize_points(Particles::ParticleHandler<dim> &particles,
                                    const BackgroundGrid<dim> &grid) const
  {
    using Layout = PropertyLayout<dim>;
    for (auto &particle : particles)
      {
        const ArrayView<double> props = particle.get_properties();
        const unsigned int      material =
          static_cast<unsigned int>(props[Layout::material_id]);
        const double n = material_porosity[material];
        props[porosity_slot()] = n;
        props[pressure_slot()] =
          n > 0 ? initial_pressure->value(
                    grid.to_scene_frame(particle.get_location())) :
                  0.;
        for (unsigned int d = 0; d < dim; ++d)
          props[velocity_slot() + d] = n > 0 ? props[Layout::velocity + d] : 0.;
        if (affine)
          for (unsigned int c = 0; c < dim * dim; ++c)
            props[affine_slot() + c] = 0;
        if (rate_averaging == RateAveraging::node)
          props[volumetric_rate_slot()] = 0;
      }
  }


  template <int dim>
  double
  PoreWater<dim>::fastest_wave_speed(const double M,
                                     const double rho_d,
                                     const double n) const
  {
    // The P waves of the two phases without drag: u_s and u_w with the
    // stiffness [[M + K (1 - n)^2, K (1 - n) n], [K (1 - n) n, K n^2]],
    // K = K_w / n, against the masses diag(rho_d, n rho_w). c^2 are the
    // eigenvalues of the 2 x 2 generalised problem; the largest bounds
    // the undrained wave (its Rayleigh quotient for u_s = u_w), the
    // skeleton's and the water's own, so the step it sets is stable
    // whatever the drag.
    const double K     = bulk_modulus / n;
    const double rho_w = n * water_density;
    const double a     = (M + K * (1 - n) * (1 - n)) / rho_d;
    const double b     = K * n * n / rho_w;
    const double trace = a + b;
    const double det   = M * K * n * n / (rho_d * rho_w);
    return std::sqrt(0.5 * trace +
                     std::sqrt(std::max(0., 0.25 * trace * trace - det)));
  }


  template <int dim>
  double
  PoreWater<dim>::max_wave_speed(const MaterialLibrary &materials) const
  {
    double c = 0;
    for (unsigned int m = 0; m < materials.size(); ++m)
      {
        const double n = materials[m].porosity;
        if (n == 0)
          continue;
        const double M     = materials[m].model->p_wave_modulus();
        const double rho_d = materials[m].density;
        c                  = std::max(c, fastest_wave_speed(M, rho_d, n));
      }
    return c;
  }


  template <int dim>
  typename PhaseKernel<dim>::Targets
  PoreWater<dim>::grid_targets()
  {
    static_assert(6 + std::tuple_size_v<decltype(wall_state_sums)> <=
                    PhaseKernel<dim>::max_targets,
                  "PoreWater's grid targets exceed PhaseKernel::max_targets.");
    typename PhaseKernel<dim>::Targets targets{{&mass,
                                                &momentum,
                                                &force,
                                                &skeleton_pressure_force,
                                                &drag,
                                                &volume_sums}};
    if (wall_excess_gradient)
      for (unsigned int t = 0; t < wall_state_sums.size(); ++t)
        targets[6 + t] = &wall_state_sums[t];
    return targets;
  }


  template <int dim>
  void
  PoreWater<dim>::add_to_grid(
    const double                                  *props,
    const Q1ShapeFunctions<dim>                   &sf,
    const typename PhaseKernel<dim>::VertexValues &offsets,
    typename PhaseKernel<dim>::Sums               &sums) const
  {
    using Layout   = PropertyLayout<dim>;
    const double n = props[porosity_slot()];
    if (n == 0)
      return;
    const unsigned int material =
      static_cast<unsigned int>(props[Layout::material_id]);
    const double         V   = props[Layout::volume];
    const double         p   = props[pressure_slot()];
    const double         m_w = water_mass(props);
    const Tensor<1, dim> v_w = read_vector<dim>(&props[velocity_slot()]);
    Tensor<2, dim>       C_w;
    if (affine)
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          C_w[a][b] = props[affine_slot() + a * dim + b];
    // Drag per unit relative velocity of the point's water.
    double k = material_permeability[material];
    if (kozeny_carman)
      {
        const double n0 = material_porosity[material];
        k *= (n * n * n / ((1 - n) * (1 - n))) /
             (n0 * n0 * n0 / ((1 - n0) * (1 - n0)));
      }
    const double Q = V * n * n * viscosity / k;
    // The state excess_wall_push() reads at the nodes: the effective
    // stress, the pore pressure and the mixture's density, packed dim to
    // a target from the seventh on.
    std::array<double, n_wall_state_values> state;
    if (wall_excess_gradient)
      {
        const SymmetricTensor<2, 3> stored =
          read_symmetric_tensor(&props[Layout::stress]);
        SymmetricTensor<2, dim> sigma;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = a; b < dim; ++b)
            sigma[a][b] = stored[a][b];
        for (unsigned int k = 0; k < n_stress_values; ++k)
          state[k] = sigma.access_raw_entry(k);
        state[n_stress_values]     = p;
        state[n_stress_values + 1] = (props[Layout::mass] + m_w) / V;
      }
    for (unsigned int i = 0; i < PhaseKernel<dim>::n_vertices; ++i)
      {
        const double N = sf.value[i];
        for (unsigned int c = 0; c < dim; ++c)
          {
            sums[0][i][c] += N * m_w;
            sums[4][i][c] += N * Q;
          }
        sums[1][i] += (N * m_w) * (affine ? v_w + C_w * offsets[i] : v_w);
        if (submerged)
          {
            // The hydrostatic part of the still water's pressure balances
            // the water's weight and lifts the skeleton by the water it
            // displaces.
            sums[2][i] += (V * n * p) * sf.gradient[i];
            sums[3][i] += (V * (1 - n) * p) * sf.gradient[i] -
                          (N * V * (1 - n) * water_density) * gravity;
          }
        else
          {
            sums[2][i] += (N * m_w) * gravity + (V * n * p) * sf.gradient[i];
            sums[3][i] += (V * (1 - n) * p) * sf.gradient[i];
          }
        // The saturated volume at the nodes, in every component.
        for (unsigned int c = 0; c < dim; ++c)
          sums[5][i][c] += N * V;
        if (wall_excess_gradient)
          for (unsigned int v = 0; v < n_wall_state_values; ++v)
            sums[6 + v / dim][i][v % dim] += (N * V) * state[v];
      }
  }


  template <int dim>
  double
  PoreWater<dim>::excess_wall_push(const std::array<unsigned int, dim> &dofs,
                                   const Tensor<1, dim> &normal) const
  {
    if (!wall_excess_gradient)
      return 0;
    const double S = volume_sums.local_element(dofs[0]);
    if (S <= 0)
      return 0;
    const auto value = [&](const unsigned int v) {
      return wall_state_sums[v / dim].local_element(dofs[v % dim]) / S;
    };
    SymmetricTensor<2, dim> sigma;
    for (unsigned int k = 0; k < n_stress_values; ++k)
      sigma.access_raw_entry(k) = value(k);
    const double p     = value(n_stress_values);
    const double rho   = value(n_stress_values + 1);
    const double total = p - normal * (sigma * normal);
    if (!(total > 0))
      return 0;
    const double r               = std::clamp(p / total, 0., 1.);
    const double g_n             = gravity * normal;
    const double excess_gradient = submerged ? r * (rho - water_density) * g_n :
                                               (r * rho - water_density) * g_n;
    return nodal_porosity.local_element(dofs[0]) * S * excess_gradient;
  }


  template <int dim>
  void
  PoreWater<dim>::couple(NodalFields                     &nodal,
                         const std::vector<unsigned int> &active_dofs,
                         const NodalVector               *boundary_forces,
                         const double                     local_damping)
  {
    const double dt = time_step;
    // Cundall's local damping at node i for the unbalanced force @p f:
    // alpha |f| against the skeleton's motion.
    const auto damping_force = [&](const unsigned int i, const double f) {
      const double v = nodal.velocity.local_element(i);
      return local_damping * std::abs(f) * (v > 0 ? 1. : v < 0 ? -1. : 0.);
    };
    for (const unsigned int i : active_dofs)
      {
        const double m_w = mass.local_element(i);
        const double m_s = nodal.mass.local_element(i);
        const double V_i = volume_sums.local_element(i);
        nodal_porosity.local_element(i) =
          V_i > 0 ? m_w / (water_density * V_i) : 0.;
        if (m_w <= 0 || m_s <= 0)
          {
            velocity.local_element(i)     = 0;
            velocity_new.local_element(i) = 0;
            // A node of dry material only: damped as in a dry scene (the
            // dry nodal update damps no node when there is pore water).
            if (local_damping > 0 && m_s > 0)
              nodal.force.local_element(i) -=
                damping_force(i, nodal.force.local_element(i));
            continue;
          }
        if (boundary_forces != nullptr)
          {
            // Water of a prescribed pressure on a boundary: the water's
            // share of its push is the nodal porosity's.
            const double F = boundary_forces->local_element(i);
            const double n = nodal_porosity.local_element(i);
            force.local_element(i) += n * F;
            skeleton_pressure_force.local_element(i) += (1 - n) * F;
          }
        const double v_s = nodal.momentum.local_element(i) / m_s;
        const double v_w = momentum.local_element(i) / m_w;
        double F_s = nodal.force.local_element(i) +
                     skeleton_pressure_force.local_element(i);
        if (local_damping > 0)
          {
            // Cundall's local damping on the mixture: against the
            // skeleton's motion, proportional to the mixture's unbalanced
            // force (the drag cancels in it), shared by the phases as
            // their masses. Damping the skeleton alone after this solve
            // let it move against its water: under undrained loading the
            // points' pore pressures then split from their effective
            // stresses cell by cell (3 % of the pressure).
            const double damping =
              damping_force(i, F_s + force.local_element(i));
            F_s -= damping * m_s / (m_s + m_w);
            force.local_element(i) -= damping * m_w / (m_s + m_w);
          }
        const double F_w = force.local_element(i);
        const double Q   = drag.local_element(i);
        // [a + Q, -Q; -Q, b + Q] [v_s'; v_w'] = [a v_s + F_s; b v_w + F_w]
        const double a   = m_s / dt;
        const double b   = m_w / dt;
        const double r_s = a * v_s + F_s;
        const double r_w = b * v_w + F_w;
        const double det = a * b + Q * (a + b);
        const double v_s_new = ((b + Q) * r_s + Q * r_w) / det;
        const double v_w_new = (Q * r_s + (a + Q) * r_w) / det;
        nodal.force.local_element(i)  = a * (v_s_new - v_s);
        velocity.local_element(i)     = v_w;
        velocity_new.local_element(i) = v_w_new;
      }
  }


  template <int dim>
  void
  PoreWater<dim>::finish_velocity(
    const NodalFields               &nodal,
    const std::vector<unsigned int> &active_dofs,
    const BoundaryConditions<dim>   &boundary_conditions)
  {
    if (boundary_conditions.has_separate_water_walls())
      {
        const double dt = time_step;
        for (const unsigned int i : active_dofs)
          {
            const double m_w = mass.local_element(i);
            if (m_w <= 0 || nodal.mass.local_element(i) <= 0)
              {
                velocity_against_held_skeleton.local_element(i) =
                  velocity_new.local_element(i);
                continue;
              }
            // m_w (v_w' - v_w) / dt = F_w - Q (v_w' - v_s')
            const double b = m_w / dt;
            const double Q = drag.local_element(i);
            velocity_against_held_skeleton.local_element(i) =
              (b * velocity.local_element(i) + force.local_element(i) +
               Q * nodal.velocity_new.local_element(i)) /
              (b + Q);
          }
        boundary_conditions.drain_at_walls(velocity_against_held_skeleton,
                                           velocity_new);
      }
    boundary_conditions.project_water_velocity(velocity_new);
  }


  template <int dim>
  typename PhaseKernel<dim>::Sources
  PoreWater<dim>::grid_sources()
  {
    Assert(skeleton_velocity != nullptr, ExcInternalError());
    return {{&velocity_new, &velocity, skeleton_velocity}};
  }


  template <int dim>
  void
  PoreWater<dim>::update_point(
    double                                                          *props,
    const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
    const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> &gradients,
    const Tensor<2, dim> &affine_fit) const
  {
    // The point's own rate in place of its cell's mean.
    update_point_with_cell_mean(props,
                                values,
                                gradients,
                                affine_fit,
                                cell_rate(props, values, gradients).first);
  }


  template <int dim>
  std::pair<double, double>
  PoreWater<dim>::cell_rate(
    const double *props,
    const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &,
    const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> &gradients)
    const
  {
    const double n = props[porosity_slot()];
    if (n == 0)
      return {0., 0.};
    return {(1 - n) * trace(gradients[2]) + n * trace(gradients[0]),
            props[PropertyLayout<dim>::volume]};
  }


  template <int dim>
  void
  PoreWater<dim>::update_point_with_cell_mean(
    double                                                          *props,
    const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
    const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> &gradients,
    const Tensor<2, dim>                                            &affine_fit,
    const double cell_mean) const
  {
    const double n = props[porosity_slot()];
    if (n == 0)
      return;
    const double   dt  = time_step;
    Tensor<1, dim> v_w = read_vector<dim>(&props[velocity_slot()]);
    if (affine)
      {
        // APIC: the nodal velocity and the affine fit about the point.
        v_w = values[0];
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            props[affine_slot() + a * dim + b] = affine_fit[a][b];
      }
    else
      v_w = flip_fraction * (v_w + values[0] - values[1]) +
            (1 - flip_fraction) * values[0];
    for (unsigned int d = 0; d < dim; ++d)
      props[velocity_slot() + d] = v_w[d];
    if (rate_averaging == RateAveraging::node)
      // The pressure follows in NodalPressureRate's pass.
      props[volumetric_rate_slot()] = cell_rate(props, values, gradients).first;
    else
      props[pressure_slot()] -= dt * bulk_modulus / n *
                                (rate_averaging == RateAveraging::none ?
                                   cell_rate(props, values, gradients).first :
                                   cell_mean);
    // The porosity follows the volume where the volume changes
    // (PointUpdate::update_porosity()).
  }


  template <int dim>
  void
  PoreWater<dim>::finish_cell(const ArrayView<double *const>    &props,
                              const ArrayView<const Point<dim>> &positions,
                              const double cell_volume) const
  {
    // With nodal rates the pressures are updated, and finished, in
    // NodalPressureRate's pass.
    if (rate_averaging != RateAveraging::node)
      finish_cell_pressures(props, positions, cell_volume);
  }


  template <int dim>
  void
  PoreWater<dim>::finish_cell_pressures(
    const ArrayView<double *const>    &props,
    const ArrayView<const Point<dim>> &positions,
    const double                       cell_volume) const
  {
    if (free_surface_fraction > 0)
      {
        double saturated_volume = 0;
        for (unsigned int q = 0; q < props.size(); ++q)
          if (props[q][porosity_slot()] > 0)
            saturated_volume += props[q][PropertyLayout<dim>::volume];
        if (saturated_volume < free_surface_fraction * cell_volume)
          {
            for (unsigned int q = 0; q < props.size(); ++q)
              if (props[q][porosity_slot()] > 0)
                props[q][pressure_slot()] = 0;
            return;
          }
      }
    if (project_pressure)
      project_cell_pressures(props, positions);
  }


  template <int dim>
  void
  PoreWater<dim>::project_cell_pressures(
    const ArrayView<double *const>    &props,
    const ArrayView<const Point<dim>> &positions) const
  {
    // The volume-weighted least-squares fit p = a + b . (x - xbar) over
    // the cell's saturated points.
    double     W = 0, a = 0;
    Point<dim> xbar;
    for (unsigned int q = 0; q < props.size(); ++q)
      if (props[q][porosity_slot()] > 0)
        {
          const double w = props[q][PropertyLayout<dim>::volume];
          W += w;
          a += w * props[q][pressure_slot()];
          xbar += w * positions[q];
        }
    if (W <= 0)
      return;
    a /= W;
    xbar /= W;
    SymmetricTensor<2, dim> S;
    Tensor<1, dim>          r;
    for (unsigned int q = 0; q < props.size(); ++q)
      if (props[q][porosity_slot()] > 0)
        {
          const double         w  = props[q][PropertyLayout<dim>::volume];
          const Tensor<1, dim> dx = positions[q] - xbar;
          S += w * symmetrize(outer_product(dx, dx));
          r += w * (props[q][pressure_slot()] - a) * dx;
        }
    // b = S^+ r, the pseudo-inverse: a cell whose points lie on a line
    // (or are one point) gets the slope along that line and none across
    // it. Exact on the directions it keeps, so that a field linear over
    // the cell is kept to round-off step after step.
    const double scale = trace(S);
    if (scale <= 0)
      return;
    Tensor<1, dim> b;
    for (const auto &[lambda, e] : eigenvectors(S))
      if (lambda > 1e-8 * scale)
        b += ((e * r) / lambda) * e;
    for (unsigned int q = 0; q < props.size(); ++q)
      if (props[q][porosity_slot()] > 0)
        props[q][pressure_slot()] = a + b * (positions[q] - xbar);
  }


  template class PoreWater<2>;
  template class PoreWater<3>;
} // namespace MPM
