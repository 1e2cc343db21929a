#!/usr/bin/env bash
# Regenerate the figures of doc/ from the shipped prm files (Release build,
# one core), by calling the scripts that make each of them.
#
# Usage: scripts/make_doc_figures.sh [figure ...]
#   (no argument: the quick ones, "flume sliding_block landslide
#   hazard_rasters column_collapse consolidation dam_break"; "all": every
#   figure below, several hours)
#
# Figures (time on one core of a shared 2-core machine, roughly):
#   flume             doc/flume_runout.png, flume_velocity.png, flume_points.png:
#                     prm/flume_usgs.prm as shipped (front and tail against
#                     time; mean velocity with the paper's peak; initial and
#                     final points), scripts/plot_flume.py (doc/flume.md).
#                     45-110 s.
#   sliding_block     doc/sliding_block.png and doc/sliding_block_errors.txt:
#                     mean speed against the analytical line for mu = 0 ...
#                     0.6, and the relative speed error,
#                     scripts/sliding_block_sweep.sh (doc/validation.md).
#                     1-2 min.
#   landslide         doc/landslide_valley_3d.png: the deposit of
#                     prm/landslide_valley_3d.prm over the ground contours,
#                     scripts/plot_landslide.py (doc/three_d.md). 15-30 s.
#   hazard_rasters    doc/hazard_rasters.png: the rasters of
#                     prm/landslide_gis_3d.prm (maximum flow height, speed,
#                     pressure, deposit) over the DEM's hillshade,
#                     scripts/plot_hazard_rasters.py (doc/gis.md). 15-30 s.
#   column_collapse   doc/column_collapse.png (and .csv): runout and final
#                     height against the aspect ratio a = 0.5 ... 6, 5 mm,
#                     with Lube et al.'s law, scripts/column_collapse_sweep.sh
#                     (doc/column_collapse.md). 2-4 min.
#   column_collapse_apic_cpdi_2p5mm
#                     doc/column_collapse_apic_cpdi_2p5mm.png (and .csv):
#                     the shipped file's path, APIC on CPDI weights, on
#                     2.5 mm, a = 3, 1, 4, 6, 0.5. 1.8 hours.
#   column_collapse_blend_2p5mm
#                     doc/column_collapse_blend_2p5mm.png (and .csv): the
#                     FLIP/PIC blend 0.98 per 6e-5 s on linear weights (an
#                     option; doc/column_collapse.md, "The blend 0.98 per
#                     6e-5 s on 5 and 2.5 mm") on 2.5 mm, a = 0.5, 1, 3, 4,
#                     6. 13 min.
#   convergence       doc/convergence.png (and convergence_bar.csv,
#                     convergence_column.csv): vibrating bar and self-weight
#                     column under refinement, linear and CPDI weights,
#                     scripts/convergence_sweep.sh (doc/convergence.md).
#                     About 15 min.
#   speed_error       doc/speed_error.png (and .csv): error against wall time,
#                     one parameter varied at a time, the four scenes of the
#                     figure (vibrating bar, self-weight column, sliding
#                     block, flume), scripts/speed_error_sweep.sh
#                     (doc/performance.md). About 12 min, 10 of them the
#                     flume.
#   slope_stability   doc/slope_stability_srm.png (and slope_stability_curve_r0/1.csv):
#                     crest displacement against the strength reduction
#                     factor on 1 m and 0.5 m cells, and the bisection of the
#                     factor of safety on 1, 0.5 and 0.25 m
#                     (slope_stability_srm_r0/1/2.csv),
#                     scripts/strength_reduction.sh (doc/slope_stability.md).
#                     About 20 min, 13 of them the 0.25 m bisection.
#   slope_runout      doc/slope_runout.png: prm/slope_runout.prm with and
#                     without softening, scripts/plot_slope_stability.py
#                     (doc/slope_stability.md). 2 min.
#   shear_band        doc/shear_band_softening.png: prm/shear_band_softening.prm
#                     local and non-local (R = 0.2 m) on 0.1, 0.05, 0.025 m
#                     cells, scripts/plot_slope_stability.py band
#                     (doc/slope_stability.md). About 7 min.
#   consolidation     doc/terzaghi_consolidation.png: prm/terzaghi_consolidation.prm,
#                     the points' excess pore pressure at T = 0.05 ... 1
#                     against Terzaghi's series, scripts/plot_pore_water.py
#                     (doc/pore_water.md). 10 s.
#   dam_break         doc/dam_break.png: prm/dam_break.prm on a / 10,
#                     a / 20 and a / 40 cells, the surge front against
#                     Martin and Moyce, scripts/plot_pore_water.py
#                     (doc/pore_water.md). 7 min.
#   slope_pore_pressure
#                     doc/infinite_slope_pore_pressure.png (and
#                     slope_stability_pore_pressure_r0/1/2.csv): the factor
#                     of safety of prm/infinite_slope_pore_pressure.prm
#                     bisected on 0.5, 0.25, 0.125 m cells against Davis'
#                     closed form, scripts/strength_reduction.sh and
#                     scripts/plot_pore_water.py (doc/slope_stability.md).
#                     About 8 min.
#
# Environment:
#   MPM_PREBUILT_DIR  a build holding mpm (and libmpm-core.so beside it):
#                     used as it is, nothing is built (scripts/setup.sh);
#                     the directory is put first on LD_LIBRARY_PATH.
#   MPM_FIGURE_WORK_DIR  where the runs write their output (default
#                     output-doc-figures in the current directory).
# The CSV files beside the figures are rewritten by the sweeps too.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
if [ -n "${MPM_PREBUILT_DIR:-}" ]; then
  export MPM_PREBUILT_DIR
  export LD_LIBRARY_PATH="$MPM_PREBUILT_DIR${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
scripts="$MPM_ROOT/scripts"
doc="$MPM_ROOT/doc"
python=/usr/bin/python3

quick=(flume sliding_block landslide hazard_rasters column_collapse
       consolidation dam_break)
every=(flume sliding_block landslide hazard_rasters column_collapse
       column_collapse_apic_cpdi_2p5mm column_collapse_blend_2p5mm
       convergence speed_error slope_stability slope_runout shear_band
       consolidation dam_break slope_pore_pressure)
figures=("$@")
[ ${#figures[@]} -gt 0 ] || figures=("${quick[@]}")
[ "${figures[*]}" != all ] || figures=("${every[@]}")
for f in "${figures[@]}"; do
  [[ " ${every[*]} " == *" $f "* ]] || { echo "unknown figure '$f'; choices: ${every[*]} (or all)" >&2; exit 1; }
done

work="${MPM_FIGURE_WORK_DIR:-output-doc-figures}"
mkdir -p "$work"
cd "$work"
apic_cpdi=(--set "Transfer/Scheme=apic" --set "Transfer/Particle-grid weights=cpdi")
blend_per_6e5=(--set "Transfer/Scheme=flip/pic blend" --set "Transfer/FLIP fraction=0.98"
               --set "Transfer/FLIP fraction time step=6e-5"
               --set "Transfer/Particle-grid weights=linear")

for f in "${figures[@]}"; do
  echo "== $f"
  start=$SECONDS
  case "$f" in
    flume)
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/flume_usgs.prm" \
        --set "Output/Directory=flume" > flume.log
      grep '^peak mean speed' flume/report.txt
      "$python" "$scripts/plot_flume.py" flume "$doc" ;;
    sliding_block)
      "$scripts/sliding_block_sweep.sh" sliding-block-sweep ;;
    landslide)
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/landslide_valley_3d.prm" \
        --set "Output/Directory=landslide-valley-3d" > landslide.log
      "$python" "$scripts/plot_landslide.py" "$MPM_ROOT/meshes/valley.asc" \
        landslide-valley-3d "$doc/landslide_valley_3d.png" ;;
    hazard_rasters)
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/landslide_gis_3d.prm" \
        --set "Output/Directory=landslide-gis-3d" \
        --set "Output/Write particles=false" > landslide_gis.log
      grep -A12 '^## hazard rasters' landslide-gis-3d/report.txt
      "$python" "$scripts/plot_hazard_rasters.py" landslide-gis-3d \
        "$MPM_ROOT/meshes/valley_utm.asc" "$doc/hazard_rasters.png" ;;
    column_collapse)
      "$scripts/column_collapse_sweep.sh" ;;
    column_collapse_blend_2p5mm)
      MPM_CELL_SIZE=0.0025 MPM_SWEEP_NAME=blend_2p5mm "$scripts/column_collapse_sweep.sh" "0.5 1 3 4 6" "${blend_per_6e5[@]}" ;;
    column_collapse_apic_cpdi_2p5mm)
      MPM_CELL_SIZE=0.0025 MPM_SWEEP_NAME=apic_cpdi_2p5mm "$scripts/column_collapse_sweep.sh" "3 1 4 6 0.5" "${apic_cpdi[@]}" ;;
    convergence)
      "$scripts/convergence_sweep.sh" ;;
    speed_error)
      "$scripts/speed_error_sweep.sh" vibrating_bar self_weight_column sliding_block flume ;;
    slope_stability)
      factors="1.2 1.25 1.3 1.325 1.35 1.375 1.4 1.425 1.45 1.475 1.5 1.55 1.6"
      for r in 0 1; do
        MPM_SRM_NAME=curve_r$r MPM_SRM_FACTORS="$factors" "$scripts/strength_reduction.sh" \
          "$MPM_ROOT/prm/slope_stability.prm" 1 2 --set "Mesh/Global refinements=$r"
      done
      for r in 0 1 2; do
        MPM_SRM_NAME=srm_r$r "$scripts/strength_reduction.sh" "$MPM_ROOT/prm/slope_stability.prm" \
          1.2 1.6 0.005 --set "Mesh/Global refinements=$r" | tail -1
      done
      "$python" "$scripts/plot_slope_stability.py" srm "$doc/slope_stability_srm.png" \
        "$doc/slope_stability_curve_r0.csv" "$doc/slope_stability_curve_r1.csv" ;;
    slope_runout)
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/slope_runout.prm" \
        --set "Output/Directory=slope-runout" > slope-runout.log
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/slope_runout.prm" \
        --set "Materials/soil/mohr coulomb/Strain softening/Enabled=false" \
        --set "Output/Directory=slope-runout-no-softening" > slope-runout-no-softening.log
      grep -E '^(front|scarp)' slope-runout/report.txt
      "$python" "$scripts/plot_slope_stability.py" runout "$doc/slope_runout.png" \
        "slope-runout:3:t = 3 s, released" "slope-runout:5:t = 5 s" "slope-runout:8:t = 8 s" \
        "slope-runout:20:t = 20 s" "slope-runout-no-softening:20:t = 20 s without softening" ;;
    shear_band)
      for r in 0 1 2; do
        for R in 0 0.2; do
          "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/shear_band_softening.prm" \
            --set "Mesh/Global refinements=$r" \
            --set "Materials/soil/mohr coulomb/Strain softening/Nonlocal radius=$R" \
            --set "Output/Directory=band-R$R-r$r" > band-R$R-r$r.log
        done
      done
      "$python" "$scripts/plot_slope_stability.py" band "$doc/shear_band_softening.png" \
        "band-R0-r0:local, 0.1 m cells" "band-R0-r1:local, 0.05 m" "band-R0-r2:local, 0.025 m" \
        "band-R0.2-r0:non-local R = 0.2 m, 0.1 m cells" "band-R0.2-r1:non-local, 0.05 m" \
        "band-R0.2-r2:non-local, 0.025 m" ;;
    consolidation)
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/terzaghi_consolidation.prm" \
        --set "Output/Directory=consolidation" > consolidation.log
      grep '^T at U' consolidation/report.txt
      "$python" "$scripts/plot_pore_water.py" consolidation \
        "$doc/terzaghi_consolidation.png" consolidation ;;
    dam_break)
      for r in 0 1 2; do
        "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/dam_break.prm" \
          --set "Mesh/Global refinements=$r" --set "Output/Write particles=false" \
          --set "Output/Directory=dam-break-r$r" > dam-break-r$r.log
      done
      grep '^largest' dam-break-r0/report.txt
      "$python" "$scripts/plot_pore_water.py" dam_break "$doc/dam_break.png" \
        "dam-break-r0/report.txt:a / 10 cells (the shipped file)" \
        "dam-break-r1/report.txt:a / 20 cells" \
        "dam-break-r2/report.txt:a / 40 cells" ;;
    slope_pore_pressure)
      prm="$MPM_ROOT/prm/infinite_slope_pore_pressure.prm"
      MPM_SRM_NAME=pore_pressure_r0 "$scripts/strength_reduction.sh" "$prm" 1.0 1.2 0.005 | tail -1
      MPM_SRM_NAME=pore_pressure_r1 "$scripts/strength_reduction.sh" "$prm" 1.07 1.11 0.005 \
        --set "Mesh/Global refinements=1" | tail -1
      MPM_SRM_NAME=pore_pressure_r2 "$scripts/strength_reduction.sh" "$prm" 1.07 1.09 0.005 \
        --set "Mesh/Global refinements=2" | tail -1
      "$python" "$scripts/plot_pore_water.py" slope_pore_pressure \
        "$doc/infinite_slope_pore_pressure.png" "$doc/slope_stability_pore_pressure_r0.csv:0.5" \
        "$doc/slope_stability_pore_pressure_r1.csv:0.25" "$doc/slope_stability_pore_pressure_r2.csv:0.125" ;;
  esac
  echo "== $f: $((SECONDS - start)) s"
done
