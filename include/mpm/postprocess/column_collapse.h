#ifndef mpm_postprocess_column_collapse_h
#define mpm_postprocess_column_collapse_h

#include <mpm/postprocess/postprocessor.h>

#include <string>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * Collapse of a granular column on a flat rough base (the base at
     * y = 'Base elevation' in 2D, z in 3D, a wall at x = 'Wall position',
     * the column of width L0 and height H0 against it, flowing towards +x;
     * in 3D the column fills a channel between slip side walls, and its
     * width across the channel is taken from its initial volume): the
     * classical test of granular flow models against the runout scalings
     * of experiments (doc/column_collapse.md).
     *
     * At output times: the front (the largest x of a point plus half its
     * spacing sqrt(V_p), i.e. the edge of the deposit) and the height (the
     * largest y plus half a spacing) and the mean speed. At the end: the
     * runout (L_inf - L0) / L0 and the height H_inf / L0 of the final
     * state against the aspect ratio a = H0 / L0, and when the mean speed
     * fell below 'Stop speed' for good; the final deposit's thickness
     * profile and three measures of its runout beside the front point's:
     * where the thickness falls below 'Front thickness', where the
     * connected deposit ends (first empty bin), and within which x lie
     * the shares 'Runout volume fractions' of the point volume. The last
     * is the one to converge under mesh refinement (APIC + CPDI at a = 4:
     * within 0.8 % over three meshes, where the threshold runout moved by
     * a quarter): the threshold
     * crossing of a thin tapering tail jumps by whole bins with the noise
     * of the tail's thickness (doc/column_collapse.md).
     */
    template <int dim>
    class ColumnCollapse : public PostprocessorWithState<dim, ColumnCollapse<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      initialize() override;

      void
      execute(const bool output_step) override;

      void
      write_report(std::ostream &report) override;

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &table &last_time_above_stop &front &height &mean_speed
          &initial_volume &width &initial_height;
      }

    private:
      /**
       * Front, height and mean speed now (collective).
       */
      std::array<double, 3>
      measure() const;

      /// L0 and H0 (initialize(): given, or measured at the start).
      double width = 0, initial_height = 0;
      /// 'Initial width' and 'Initial height' (0: 'auto').
      double given_width = 0, given_height = 0;
      double base = 0, wall = 0, stop_speed = 0.01, bin_width = 0.005,
             front_thickness = 0.01;
      /// 'Runout volume fractions'.
      std::vector<double> volume_fractions{0.95, 0.99};

      std::string table;
      double      last_time_above_stop = 0;
      double      front = 0, height = 0, mean_speed = 0;
      /// The points' total volume at the start (their bulking at the end
      /// is reported).
      double      initial_volume = 0;
    };
  } // namespace Postprocessors
} // namespace MPM

#endif
