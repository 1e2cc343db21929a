#include <mpm/base/input_error.h>
#include <mpm/transfer/velocity_transfer.h>

namespace MPM
{
  template <int dim>
  void
  VelocityTransfer<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Transfer");
    {
      prm.declare_entry(
        "Scheme",
        "apic",
        Patterns::Selection(TransferSchemeRegistry<dim>::names()),
        "How point velocities go to the grid and back (doc/transfers.md "
        "compares them). 'apic' (the default, with the default "
        "'Particle-grid weights = cpdi' and 'Time stepping/Update scheme "
        "= MUSL'): affine particle-in-cell (Jiang et al. 2015): points "
        "carry an affine velocity field that particle-to-grid keeps "
        "exactly, so rotation and shear survive the transfer; on CPDI "
        "weights its matrix is fitted to the end-of-step grid velocity "
        "(C = B D^-1) under every update scheme. The path that converges "
        "under refinement: a sheared elastic layer exact to 1e-4 of G, "
        "collapse runouts within 1 % from 2.5 to 1.25 mm "
        "(doc/transfers.md). With linear weights, under MUSL it is the "
        "velocity gradient of the MUSL remap (stable, but dissipative as "
        "PIC), under USF and USL the fit (unstable above CFL 0.05: D "
        "vanishes on cell edges). 'flip/pic blend': v_p <- theta (v_p + dt "
        "S+ a) + (1 - theta) S+ v with theta = 'FLIP fraction' (0 = PIC: "
        "strongly dissipative; 1 = FLIP: noisy); on linear weights a third "
        "to a fifth of the default's wall time (doc/performance.md), but "
        "its damping, not "
        "the physics, sets granular runouts, which then move by 8-13 % "
        "per mesh halving, and FLIP on linear weights shears the elastic "
        "layer 16 % off the closed form (doc/transfers.md). 'xpic': "
        "XPIC(m) (Hammerquist and Nairn 2017), PIC from a grid velocity "
        "in which the round trip's smoothing is undone to order m.");
      prm.declare_entry("FLIP fraction",
                        "1",
                        Patterns::Double(0, 1),
                        "theta of 'flip/pic blend': 1 = FLIP (add the "
                        "interpolated nodal acceleration), 0 = PIC (take the "
                        "interpolated nodal velocity).");
      prm.declare_entry(
        "FLIP fraction time step",
        "0",
        Patterns::Double(0),
        "The time (s) over which the blend keeps the share 'FLIP fraction' "
        "of the point velocities' part that the grid does not represent: a "
        "step of length dt keeps theta^(dt / this), so the blend damps the "
        "same per unit time at every CFL number and mesh. 0: theta every "
        "step, whatever its length (then halving the time step doubles the "
        "damping; doc/transfers.md). The granular scenes ship with their "
        "CFL 0.5 step on their 5 mm mesh.");
      prm.declare_entry("XPIC order",
                        "2",
                        Patterns::Integer(1, 20),
                        "m of 'xpic': each order beyond 1 costs one more "
                        "particle-grid round trip of the velocity per step; "
                        "1 is PIC.");
      prm.declare_entry("APIC energy limit",
                        "true",
                        Patterns::Bool(),
                        "'apic' only: scale a point's affine matrix down "
                        "where it would carry more kinetic energy than at "
                        "the transfer that computed it (bilinear functions' "
                        "second moment vanishes on cell edges; without the "
                        "limit APIC creates energy, doc/transfers.md).");
    }
    prm.leave_subsection();
  }


  template <int dim>
  void
  VelocityTransfer<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Transfer");
    transfer_scheme = TransferSchemeRegistry<dim>::create(prm.get("Scheme"),
                                                          "Transfer/Scheme",
                                                          prm);
    prm.leave_subsection();
    apic_scheme = dynamic_cast<const Apic<dim> *>(transfer_scheme.get());
  }


  template class VelocityTransfer<2>;
  template class VelocityTransfer<3>;
} // namespace MPM
