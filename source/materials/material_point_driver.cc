#include <deal.II/base/exceptions.h>

#include <mpm/base/input_error.h>
#include <mpm/base/plugin_registry.h>
#include <mpm/materials/material_point_driver.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace MPM
{
  namespace
  {
    /// Mean pressure (compression positive).
    double
    mean_pressure(const SymmetricTensor<2, 3> &stress)
    {
      return -trace(stress) / 3. + 0.; // no "-0"
    }


    /// The von Mises stress sqrt(3 J2).
    double
    deviator_stress(const SymmetricTensor<2, 3> &stress)
    {
      const SymmetricTensor<2, 3> s = deviator(stress);
      return std::sqrt(1.5 * scalar_product(s, s));
    }
  } // namespace


  void
  MaterialPointDriver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material point driver");
    {
      prm.declare_entry("Material",
                        "",
                        Patterns::Anything(),
                        "The material of 'Materials' the point is made of "
                        "(empty: the first of 'List of materials'). Only "
                        "read by 'mpm --material-point-driver'.");
      prm.declare_entry(
        "Path",
        "simple shear",
        Patterns::Selection("simple shear|cyclic simple shear|oedometer|"
                            "undrained triaxial|drained triaxial"),
        "The strain or stress path (compression negative; the axial "
        "direction is y). 'simple shear': v_x = gamma_dot y. 'cyclic simple "
        "shear': gamma 0 -> +A -> -A -> 0 per cycle. 'oedometer': axial "
        "compression, no lateral strain. 'undrained triaxial': axial "
        "compression at constant volume. 'drained triaxial': axial "
        "compression with the lateral stresses held at the confining "
        "pressure.");
      prm.declare_entry("Final strain",
                        "0.1",
                        Patterns::Double(0),
                        "The shear strain gamma (simple shear; the amplitude "
                        "A of the cyclic one) or the axial compressive "
                        "strain (oedometer, triaxial) at the end of the "
                        "path, > 0.");
      prm.declare_entry("Number of steps",
                        "1000",
                        Patterns::Integer(1),
                        "Equal strain increments along the path (per "
                        "cycle for the cyclic one).");
      prm.declare_entry("Cell size",
                        "0",
                        Patterns::Double(0),
                        "The size (m) of the background cell the point "
                        "would sit in, for a model regularised by the cell "
                        "size (MaterialModel::update_stress_in_cell()); 0: "
                        "no cell, such a model uses its reference values.");
      prm.declare_entry("Cycles",
                        "1",
                        Patterns::Integer(1),
                        "Cycles of 'cyclic simple shear'.");
      prm.declare_entry("Confining pressure",
                        "0",
                        Patterns::Double(0),
                        "The initial isotropic pressure p0 in Pa (the "
                        "point starts from the stress -p0 I); 'drained "
                        "triaxial' holds the lateral stresses at -p0.");
      prm.declare_entry("Duration",
                        "1",
                        Patterns::Double(0),
                        "The time the path takes in s (the strain rate of "
                        "rate-dependent models), > 0.");
    }
    prm.leave_subsection();
  }


  void
  MaterialPointDriver::parse_parameters(ParameterHandler &prm)
  {
    materials.parse_parameters(prm);
    // A strength reduction factor applies along the whole path: its value
    // at t = 0.
    materials.set_time(0);
    prm.enter_subsection("Material point driver");
    const std::string name = prm.get("Material");
    material_index =
      name.empty() ? 0 :
                     materials.index_of(name, "Material point driver/Material");
    path = select_choice<Path>(
      prm.get("Path"),
      {{"simple shear", Path::simple_shear},
       {"cyclic simple shear", Path::cyclic_simple_shear},
       {"oedometer", Path::oedometer},
       {"undrained triaxial", Path::undrained_triaxial},
       {"drained triaxial", Path::drained_triaxial}},
      "Material point driver/Path");
    final_strain = prm.get_double("Final strain");
    check_input(final_strain > 0,
                "Material point driver/Final strain = " +
                  prm.get("Final strain") + ": must be > 0.");
    n_steps            = prm.get_integer("Number of steps");
    cell_size          = prm.get_double("Cell size");
    n_cycles           = prm.get_integer("Cycles");
    confining_pressure = prm.get_double("Confining pressure");
    duration           = prm.get_double("Duration");
    check_input(duration > 0,
                "Material point driver/Duration = " + prm.get("Duration") +
                  ": must be > 0 (s).");
    if (path != Path::cyclic_simple_shear)
      n_cycles = 1;
    prm.leave_subsection();
    prm.enter_subsection("Output");
    directory = prm.get("Directory");
    prm.leave_subsection();
  }


  double
  MaterialPointDriver::path_strain(const unsigned int n) const
  {
    if (path != Path::cyclic_simple_shear)
      return final_strain * n / n_steps;
    // A triangle wave of amplitude A, n_steps steps per cycle.
    const double phase = std::fmod(4. * n / n_steps, 4.);
    const double shape = phase <= 1 ? phase : (phase <= 3 ? 2 - phase : phase - 4);
    return final_strain * shape;
  }


  Tensor<2, 3>
  MaterialPointDriver::velocity_gradient(const unsigned int n,
                                         const double       dt) const
  {
    const double rate = (path_strain(n + 1) - path_strain(n)) / dt;
    Tensor<2, 3> L;
    switch (path)
      {
        case Path::simple_shear:
        case Path::cyclic_simple_shear:
          L[0][1] = rate;
          break;
        case Path::oedometer:
        case Path::drained_triaxial:
          L[1][1] = -rate;
          break;
        case Path::undrained_triaxial:
          L[1][1] = -rate;
          L[0][0] = L[2][2] = 0.5 * rate;
          break;
      }
    return L;
  }


  MaterialPointDriver
  MaterialPointDriver::from_text(const std::string &parameters,
                                 const std::string &output_directory)
  {
    ParameterHandler names_prm;
    MaterialLibrary::declare_name_list(names_prm);
    names_prm.parse_input_from_string(parameters, "", true);

    ParameterHandler prm;
    MaterialLibrary::declare_parameters(prm,
                                        MaterialLibrary::read_name_list(
                                          names_prm));
    declare_parameters(prm);
    prm.enter_subsection("Output");
    prm.declare_entry("Directory", ".", Patterns::Anything());
    prm.leave_subsection();
    prm.parse_input_from_string(parameters);
    prm.enter_subsection("Output");
    prm.set("Directory", output_directory);
    prm.leave_subsection();

    MaterialPointDriver driver;
    driver.parse_parameters(prm);
    return driver;
  }


  MaterialPointDriver::History
  MaterialPointDriver::run_path() const
  {
    const Material    &material = materials[material_index];
    const unsigned int n_state  = material.model->n_state_variables();
    const unsigned int n_total  = n_steps * n_cycles;
    const double       dt       = duration / n_total;

    History history;
    history.records.reserve(n_total + 1);

    SymmetricTensor<2, 3> stress = -confining_pressure *
                                   unit_symmetric_tensor<3>();
    std::vector<double> state(n_state, 0.);
    material.model->initialize_state(ArrayView<double>(state));

    // The initial shear modulus, probed by a small shear increment (the
    // closed form of simple shear is stated with it).
    double shear_modulus = 0;
    {
      SymmetricTensor<2, 3> probe = stress;
      std::vector<double>   probe_state = state;
      SymmetricTensor<2, 3> increment;
      const double          delta = 1e-9;
      increment[0][1]             = 0.5 * delta;
      material.model->update_stress_in_cell(increment,
                                            probe,
                                            ArrayView<double>(probe_state),
                                            dt,
                                            cell_size);
      shear_modulus = (probe[0][1] - stress[0][1]) / delta;
    }
    history.shear_modulus = shear_modulus;

    double                volumetric_strain = 0;
    SymmetricTensor<2, 3> strain;
    const auto            record = [&](const unsigned int n) {
      history.records.push_back(
        Record{n, n * dt, path_strain(n), volumetric_strain, strain, stress,
               state});
    };
    record(0);

    for (unsigned int n = 0; n < n_total; ++n)
      {
        Tensor<2, 3> L = velocity_gradient(n, dt);
        // One point stands for a homogeneous body: a regularised variable
        // is its own value, (1 - m) v + m v (the MPM step sets it from the
        // neighbours, NonlocalAveraging).
        if (const auto *nonlocal = material.model->nonlocal_variable())
          state[nonlocal->nonlocal_variable] = state[nonlocal->local_variable];
        if (path == Path::drained_triaxial)
          {
            // The lateral strain rate x (L_xx = L_zz = x) that keeps
            // sigma_xx at -p0: regula falsi (Illinois) on a bracket.
            const auto residual = [&](const double x) {
              Tensor<2, 3> trial_L = L;
              trial_L[0][0] = trial_L[2][2] = x;
              SymmetricTensor<2, 3> trial = stress;
              std::vector<double>   trial_state = state;
              materials.update_stress<3>(material,
                                         trial_L,
                                         dt,
                                         trial,
                                         ArrayView<double>(trial_state),
                                         cell_size);
              return trial[0][0] + confining_pressure;
            };
            const double axial = std::abs(L[1][1]);
            double       lo = -10 * axial, hi = 10 * axial;
            double       f_lo = residual(lo), f_hi = residual(hi);
            if (!(f_lo <= 0 && f_hi >= 0))
              throw std::runtime_error(
                "Material point driver, drained triaxial, step " +
                std::to_string(n) +
                ": no lateral strain rate within 10 times the axial one "
                "holds the lateral stress at the confining pressure (the "
                "model may have lost all strength).");
            const double tolerance =
              1e-12 * (confining_pressure + shear_modulus * axial * dt) +
              1e-300;
            double       x = 0, f = 0;
            int          side = 0;
            unsigned int it   = 0;
            for (; it < 200; ++it)
              {
                x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
                f = residual(x);
                if (std::abs(f) <= tolerance || hi - lo < 1e-15 * axial)
                  break;
                if (f < 0)
                  {
                    lo = x, f_lo = f;
                    if (side == -1)
                      f_hi *= 0.5;
                    side = -1;
                  }
                else
                  {
                    hi = x, f_hi = f;
                    if (side == 1)
                      f_lo *= 0.5;
                    side = 1;
                  }
              }
            history.max_iterations = std::max(history.max_iterations, it + 1);
            L[0][0] = L[2][2] = x;
          }
        const SymmetricTensor<2, 3> strain_increment =
          materials.update_stress<3>(
            material, L, dt, stress, ArrayView<double>(state), cell_size);
        volumetric_strain += trace(strain_increment);
        strain += strain_increment;
        record(n + 1);
      }
    return history;
  }


  void
  MaterialPointDriver::run() const
  {
    const Material &material = materials[material_index];
    const History   history  = run_path();
    const double    shear_modulus = history.shear_modulus;

    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    std::ofstream csv(directory + "/stress_strain.csv");
    check_input(static_cast<bool>(csv),
                "Cannot write '" + directory +
                  "/stress_strain.csv' (parameter 'Output/Directory').");
    csv << std::setprecision(10)
        << "step,time,path_strain,volumetric_strain,sxx,syy,szz,sxy,syz,sxz,"
           "p,q";
    for (const auto &name : material.model->state_variable_names())
      csv << ',' << name;
    csv << '\n';
    for (const Record &r : history.records)
      {
        csv << r.step << ',' << r.time << ',' << r.path_strain << ','
            << r.volumetric_strain << ',' << r.stress[0][0] << ','
            << r.stress[1][1] << ',' << r.stress[2][2] << ','
            << r.stress[0][1] << ',' << r.stress[1][2] << ','
            << r.stress[0][2] << ',' << mean_pressure(r.stress) << ','
            << deviator_stress(r.stress);
        for (const double s : r.state)
          csv << ',' << s;
        csv << '\n';
      }

    const bool shear = path == Path::simple_shear ||
                       path == Path::cyclic_simple_shear;
    const bool jaumann = materials.objective_stress_rate().type() ==
                         ObjectiveStressRate::Type::jaumann;
    // The hypoelastic closed form of simple shear (Dienes 1979) with the
    // probed modulus: Jaumann sigma_xy = G sin(gamma), sigma_xx =
    // -sigma_yy = G (1 - cos(gamma)); fixed axes sigma_xy = G gamma.
    double max_deviation = 0;
    if (shear && shear_modulus > 0)
      for (unsigned int i = 1; i < history.records.size(); ++i)
        {
          const SymmetricTensor<2, 3> &stress = history.records[i].stress;
          const double gamma = history.records[i].path_strain;
          const double sxy   = jaumann ? shear_modulus * std::sin(gamma) :
                                         shear_modulus * gamma;
          const double sxx =
            jaumann ? shear_modulus * (1 - std::cos(gamma)) : 0.;
          const double p0 = -confining_pressure;
          max_deviation =
            std::max(max_deviation,
                     std::max({std::abs(stress[0][1] - sxy),
                               std::abs(stress[0][0] - p0 - sxx),
                               std::abs(stress[1][1] - p0 + sxx)}) /
                       shear_modulus);
        }

    const Record      &last    = history.records.back();
    const unsigned int n_state = last.state.size();
    std::ostringstream report;
    report << std::setprecision(8);
    report << "material point driver\n"
           << "material: " << material.name << "\n"
           << "path: "
           << (path == Path::simple_shear         ? "simple shear" :
               path == Path::cyclic_simple_shear ? "cyclic simple shear" :
               path == Path::oedometer           ? "oedometer" :
               path == Path::undrained_triaxial  ? "undrained triaxial" :
                                                   "drained triaxial")
           << "\n"
           << "objective stress rate: " << (jaumann ? "jaumann" : "none")
           << "\n"
           << "steps: " << last.step << "\n"
           << "initial shear modulus (probed) [Pa]: " << shear_modulus << "\n"
           << "final path strain: " << last.path_strain << "\n"
           << "final volumetric strain: " << last.volumetric_strain << "\n"
           << "final stress xx yy zz xy [Pa]: " << last.stress[0][0] << ' '
           << last.stress[1][1] << ' ' << last.stress[2][2] << ' '
           << last.stress[0][1] << "\n"
           << "final p, q [Pa]: " << mean_pressure(last.stress) << ' '
           << deviator_stress(last.stress) << "\n";
    if (n_state > 0)
      {
        report << "final state:";
        const auto names = material.model->state_variable_names();
        for (unsigned int i = 0; i < n_state; ++i)
          report << ' ' << names[i] << '=' << last.state[i];
        report << "\n";
      }
    if (shear && shear_modulus > 0)
      report << "max deviation from the hypoelastic closed form / G "
                "(Dienes 1979; an elastic model's integration error): "
             << max_deviation << "\n";
    if (path == Path::drained_triaxial)
      report << "most iterations for the lateral strain in a step: "
             << history.max_iterations << "\n";
    std::ofstream(directory + "/report.txt") << report.str();
    std::cout << report.str();
  }
} // namespace MPM
