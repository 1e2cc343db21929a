#ifndef mpm_postprocess_flume_h
#define mpm_postprocess_flume_h

#include <deal.II/base/point.h>

#include <mpm/postprocess/postprocessor.h>

#include <sstream>
#include <vector>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * Granular flow down the USGS flume (Tjung et al., "Flume Test";
     * Denlinger and Iverson 2001): an incline at angle theta joined to a
     * horizontal runout by a circular arc of radius R tangent to both. The
     * incline and the runout, produced, meet at the "break point" (x_b,
     * y_b); the runout is y = y_b, x > x_b + R tan(theta/2), the incline
     * rises towards -x. Positions along the bed, s, are arc lengths from the
     * midpoint of the arc, negative upslope; a point's s and its height h
     * normal to the bed are those of its nearest bed point (2D only).
     *
     * Reports at output times the front (largest s of any point) and the
     * tail (smallest s) as s and as x, the mean velocity magnitude
     * (1/N sum |v_p|, every point weighted equally, as the paper's Figure 9)
     * and the mean velocity components. At the end: the peak of the mean
     * speed (checked at every step) and its time, when the mean speed fell
     * below 'Stop speed' for good, when the front came to rest (within
     * 'Front tolerance' of its final position at every later output time),
     * the final deposit profile (per bin of s: volume per unit width over
     * the bin width, i.e. the mean thickness normal to the bed, and the
     * largest h of the bin's points) and where the deposit is thickest.
     */
    template <int dim>
    class Flume : public PostprocessorWithState<dim, Flume<dim>>
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
       * Distance s along the bed and height h normal to it of the point
       * (x, y) (scene frame).
       */
      std::pair<double, double>
      bed_coordinates(const double x, const double y) const;

      /**
       * The bed point at distance s.
       */
      Point<2>
      bed_point(const double s) const;

      /**
       * The state accumulated over the run (checkpoints).
       */
      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &peak_speed &peak_time &last_time_above_stop &first_time_after
          &end_speed &n_points_initial &samples;
      }

    private:
      struct Sample
      {
        double time, s_front, s_tail, x_front, x_tail, mean_speed;
        double mean_velocity[2];

        template <class Archive>
        void
        serialize(Archive &ar, const unsigned int)
        {
          ar &time &s_front &s_tail &x_front &x_tail &mean_speed &mean_velocity;
        }
      };

      Sample
      sample() const;

      double theta = 0, radius = 0.1, bin_width = 0.01, stop_speed = 0.01,
             front_tolerance = 0.001;
      Point<2> break_point;
      /// 'Runout volume fractions'.
      std::vector<double> volume_fractions;

      double              peak_speed = 0, peak_time = 0;
      double              last_time_above_stop = -1, first_time_after = -1;
      double              end_speed        = 0;
      unsigned long long  n_points_initial = 0;
      std::vector<Sample> samples;
    };
  } // namespace Postprocessors
} // namespace MPM

#endif
