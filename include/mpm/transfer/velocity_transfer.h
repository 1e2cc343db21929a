#ifndef mpm_transfer_velocity_transfer_h
#define mpm_transfer_velocity_transfer_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/transfer/apic.h>
#include <mpm/transfer/transfer_scheme.h>

#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The subsection 'Transfer' of the parameter file: the entries shared by
   * the velocity transfer schemes (TransferScheme: FLIP/PIC blend, XPIC,
   * APIC) and the scheme it chooses. doc/transfers.md has the measured
   * comparison of the schemes.
   */
  template <int dim>
  class VelocityTransfer
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /// The chosen scheme (after parse_parameters()).
    TransferScheme<dim> &
    scheme()
    {
      return *transfer_scheme;
    }

    const TransferScheme<dim> &
    scheme() const
    {
      return *transfer_scheme;
    }

    /// The scheme if it is APIC, else nullptr: for the particle-grid
    /// weights and passes, which do APIC's arithmetic on their entries.
    /// The rest of the code asks scheme().carries_affine_velocity().
    const Apic<dim> *
    apic() const
    {
      return apic_scheme;
    }

  private:
    std::unique_ptr<TransferScheme<dim>> transfer_scheme;
    const Apic<dim>                     *apic_scheme = nullptr;
  };
} // namespace MPM

#endif
