#ifndef mpm_postprocess_postprocessor_h
#define mpm_postprocess_postprocessor_h

#include <deal.II/base/parameter_handler.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <mpm/base/plugin_registry.h>
#include <mpm/solver/simulator_access.h>

#include <memory>
#include <ostream>
#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * A postprocessor watches the run and compares it with a reference
   * (an analytical solution, a conservation law). It is called after
   * every step and writes its findings, numbers beside their reference, to
   * the run's report (report.txt in the output directory), which is also
   * what the regression tests compare.
   *
   * Selected in "Postprocess/List of postprocessors"; each has a
   * subsection of its own for its parameters.
   *
   * It reaches the run through its SimulatorAccess (this->get_time(),
   * this->get_particle_handler(), this->compute_statistics(), ...): the
   * Simulator attaches it (initialize_simulator()) after creating it and
   * before initialize(). Created without a run (a unit test reading a
   * postprocessor's geometry), it has no simulator and must not ask for
   * one.
   */
  template <int dim>
  class Postprocessor : public SimulatorAccess<dim>
  {
  public:
    virtual ~Postprocessor() = default;

    virtual void
    parse_parameters(ParameterHandler &prm)
    {
      (void)prm;
    }

    /**
     * Called once after the points were created, before the first step.
     */
    virtual void
    initialize()
    {
    }

    /**
     * Called after every step; @p output_step tells whether this step is an
     * output time.
     */
    virtual void
    execute(const bool output_step) = 0;

    /**
     * Called at the end of the run; write the summary to @p report.
     */
    virtual void
    write_report(std::ostream &report) = 0;

    /**
     * Write what this postprocessor accumulated over the run (maxima,
     * tables, reference values taken in initialize()) to a checkpoint. A
     * resumed run calls load_state() instead of initialize(), so that its
     * report is the report of an uninterrupted run. There is no default:
     * a postprocessor that forgot its state would report only what it saw
     * after the restart; one without state says so with an empty body.
     * PostprocessorWithState implements both from a serialize() member.
     */
    virtual void
    save_state(std::ostream &out) const = 0;

    virtual void
    load_state(std::istream &in) = 0;
  };


  /**
   * Write @p object, which has a boost serialize() member, to @p out.
   */
  template <typename T>
  void
  save_object(std::ostream &out, const T &object)
  {
    boost::archive::binary_oarchive archive(out);
    archive << object;
  }

  /**
   * Read @p object written by save_object().
   */
  template <typename T>
  void
  load_object(std::istream &in, T &object)
  {
    boost::archive::binary_iarchive archive(in);
    archive >> object;
  }


  /**
   * A postprocessor whose state is its members named in its serialize()
   * member (boost): save_state() and load_state() write and read them
   * (save_object(), load_object()). Derive as
   * `class Name : public PostprocessorWithState<dim, Name<dim>>`.
   */
  template <int dim, typename Derived>
  class PostprocessorWithState : public Postprocessor<dim>
  {
  public:
    void
    save_state(std::ostream &out) const override
    {
      save_object(out, static_cast<const Derived &>(*this));
    }

    void
    load_state(std::istream &in) override
    {
      load_object(in, static_cast<Derived &>(*this));
    }
  };


  /**
   * The registry of postprocessors: each one's file ends with
   * MPM_REGISTER_POSTPROCESSOR; its parameters are in its subsection of
   * 'Postprocess'.
   */
  template <int dim>
  using PostprocessorRegistry = PluginRegistry<Postprocessor<dim>>;


  namespace Postprocessors
  {
    /**
     * Names joined by '|' for Patterns::MultipleSelection.
     */
    template <int dim>
    std::string
    names();

    /// Every postprocessor's subsection of 'Postprocess'.
    template <int dim>
    void
    declare_parameters(ParameterHandler &prm);

    /**
     * Create the postprocessor @p name and let it read its subsection of
     * "Postprocess"; an unknown name is an InputError listing the choices.
     */
    template <int dim>
    std::unique_ptr<Postprocessor<dim>>
    create(const std::string &name, ParameterHandler &prm);
  } // namespace Postprocessors
} // namespace MPM

/**
 * Register the postprocessor @p classname (templated on dim, default
 * constructible, with a static declare_parameters(ParameterHandler &))
 * under @p name, for 2D and 3D, at the end of its file.
 */
#define MPM_REGISTER_POSTPROCESSOR(classname, name, description)           \
  MPM_REGISTER_PLUGIN(MPM::PostprocessorRegistry<2>,                       \
                      name,                                                \
                      description,                                         \
                      &classname<2>::declare_parameters,                   \
                      [](dealii::ParameterHandler &prm) {                  \
                        std::unique_ptr<MPM::Postprocessor<2>> p =         \
                          std::make_unique<classname<2>>();                \
                        p->parse_parameters(prm);                          \
                        return p;                                          \
                      })                                                   \
  MPM_REGISTER_PLUGIN(MPM::PostprocessorRegistry<3>,                       \
                      name,                                                \
                      description,                                         \
                      &classname<3>::declare_parameters,                   \
                      [](dealii::ParameterHandler &prm) {                  \
                        std::unique_ptr<MPM::Postprocessor<3>> p =         \
                          std::make_unique<classname<3>>();                \
                        p->parse_parameters(prm);                          \
                        return p;                                          \
                      })

#endif
