#include <mpm/postprocess/postprocessor.h>

namespace MPM
{
  namespace Postprocessors
  {
    template <int dim>
    std::string
    names()
    {
      return PostprocessorRegistry<dim>::names();
    }


    template <int dim>
    void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Postprocess");
      PostprocessorRegistry<dim>::declare_parameters(prm);
      prm.leave_subsection();
    }


    template <int dim>
    std::unique_ptr<Postprocessor<dim>>
    create(const std::string &name, ParameterHandler &prm)
    {
      prm.enter_subsection("Postprocess");
      auto p = PostprocessorRegistry<dim>::create(
        name, "Postprocess/List of postprocessors", prm);
      prm.leave_subsection();
      return p;
    }


    template std::string
    names<2>();
    template std::string
    names<3>();
    template void
    declare_parameters<2>(ParameterHandler &);
    template void
    declare_parameters<3>(ParameterHandler &);
    template std::unique_ptr<Postprocessor<2>>
    create<2>(const std::string &, ParameterHandler &);
    template std::unique_ptr<Postprocessor<3>>
    create<3>(const std::string &, ParameterHandler &);
  } // namespace Postprocessors
} // namespace MPM
