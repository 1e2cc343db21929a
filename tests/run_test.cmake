# Runs one regression test and compares its output with the expected one.
#  - prm tests (PRM set): `mpm [BASE] PRM --set "Output/Directory=WORKDIR"`
#    (BASE from a line "# base: FILE" in PRM); compares WORKDIR/report.txt
#    with EXPECTED, or with the file named by "# expected output: FILE".
#    Tests named bad_input_* or error_* must stop with a non-zero exit code;
#    their stderr is compared instead. Tests whose name starts with bad_input_
#    must fail with a non-zero exit code; their stderr is compared instead.
#    With RANKS > 1 (tests NAME.mpirun=N), mpm runs on RANKS MPI ranks;
#    each rank on "# threads: N" threads (default 1, or $MPM_TEST_THREADS).
#  - unit tests (EXECUTABLE set): run it in WORKDIR (with the ';'-separated
#    list ARGS, if set), compare its stdout.
# Tolerances: a line "# numdiff: <options>" in the .prm (or in the unit
# test's expected output's first line), else -a 1e-10 -r 1e-8.
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})

# Open MPI's start-up, unless the environment says otherwise: a process
# started without mpirun does not launch a daemon (ess_singleton_isolated),
# and the point-to-point layer is ob1 over shared memory, not UCX's, whose
# set-up probes the network. MPI_Init then takes 0.06 s instead of 0.45 s
# (Open MPI 4.1, 2026-11-28); a few hundred tests start mpm. Neither
# changes what the ranks compute or exchange. Isolated singletons share
# one job id and so one session directory (/tmp/ompi.HOST.0/jf.0/1):
# when two tests open a checkpoint (MPI-IO) at once, the shared-file-
# pointer component 'sm' of one found the other's backing file gone and
# printed "mca_sharedfp_sm_component_file_query: Error, unable to open
# file for mmap" into a compared stderr (error_stiff_block_cfl3_restart,
# once in five clean-clone runs). The code uses no shared file pointers
# (deal.II writes at explicit offsets): that component is left out.
if(NOT DEFINED ENV{OMPI_MCA_ess_singleton_isolated})
  set(ENV{OMPI_MCA_ess_singleton_isolated} 1)
endif()
if(NOT DEFINED ENV{OMPI_MCA_pml})
  set(ENV{OMPI_MCA_pml} ob1)
endif()
if(NOT DEFINED ENV{OMPI_MCA_sharedfp})
  set(ENV{OMPI_MCA_sharedfp} ^sm)
endif()
# The shared session directory itself raced too: one singleton removed
# /tmp/ompi.HOST.0/jf.0 at its end while another created jf.0/1 in it, and
# the second stopped in MPI_Init with "A call to mkdir was unable to create
# the desired directory" (bad_input_mu_i_friction, once; exit code 1
# instead of 2). Each test's singletons get a session directory base of
# their own. (Not under mpirun, which makes a directory of its own per job,
# and whose sockets there must keep to 108 characters of path.)
if(NOT DEFINED ENV{OMPI_MCA_orte_tmpdir_base} AND NOT RANKS GREATER 1)
  file(MAKE_DIRECTORY ${WORKDIR}/mpi-session)
  set(ENV{OMPI_MCA_orte_tmpdir_base} ${WORKDIR}/mpi-session)
endif()

set(_numdiff_options -a 1e-10 -r 1e-8)
if(PRM)
  file(STRINGS ${PRM} _tol REGEX "^# numdiff:")
else()
  file(STRINGS ${EXPECTED} _tol REGEX "^# numdiff:")
endif()
if(_tol)
  string(REGEX REPLACE "^# numdiff:[ ]*" "" _tol "${_tol}")
  separate_arguments(_numdiff_options UNIX_COMMAND "${_tol}")
endif()

get_filename_component(_name ${EXPECTED} NAME_WE)
if(PRM)
  get_filename_component(_prm_dir ${PRM} DIRECTORY)
  # "# base: FILE": the test only overrides entries of FILE (a shipped case
  # or another test, path relative to the file that names it); mpm reads
  # FILE, then the test's .prm. FILE may have a base of its own: the chain
  # is read from its root.
  set(_files ${PRM})
  set(_current ${PRM})
  set(_more 1)
  while(_more)
    file(STRINGS ${_current} _base REGEX "^# base:")
    if(_base)
      string(REGEX REPLACE "^# base:[ ]*" "" _base "${_base}")
      get_filename_component(_current_dir ${_current} DIRECTORY)
      set(_current ${_current_dir}/${_base})
      list(FIND _files ${_current} _seen)
      if(NOT _seen EQUAL -1)
        message(FATAL_ERROR "${_name}: the '# base:' lines form a cycle at ${_current}")
      endif()
      list(PREPEND _files ${_current})
    else()
      set(_more 0)
    endif()
  endwhile()
  # "# expected output: OTHER.output": compare with another test's expected
  # output (e.g. a rotated scene must reproduce the unrotated one).
  file(STRINGS ${PRM} _other REGEX "^# expected output:")
  if(_other AND RANKS EQUAL 1)
    string(REGEX REPLACE "^# expected output:[ ]*" "" _other "${_other}")
    set(EXPECTED ${_prm_dir}/${_other})
  endif()
  # On several ranks (RANKS > 1): through mpirun, allowed to run as root
  # (CI containers) and on fewer cores than ranks.
  set(_launcher)
  if(RANKS GREATER 1)
    set(_launcher ${MPIEXEC} -np ${RANKS} --oversubscribe)
    set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)
    set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
  endif()
  # Threads per rank: "# threads: N" in the .prm, else the environment's
  # MPM_TEST_THREADS (the whole suite on N threads: the outputs must not
  # change), else 1 (ctest -j already fills the cores).
  set(_threads 1)
  if(DEFINED ENV{MPM_TEST_THREADS})
    set(_threads $ENV{MPM_TEST_THREADS})
  endif()
  file(STRINGS ${PRM} _threads_line REGEX "^# threads:")
  if(_threads_line)
    string(REGEX REPLACE "^# threads:[ ]*" "" _threads "${_threads_line}")
  endif()
  # Steps, in the order of their lines (default: one run):
  #  "# run: ARGS"      run mpm with these extra arguments; every run but
  #                     the last must succeed, the last is the one judged;
  #                     %WORKDIR% in ARGS is the test's folder;
  #  "# truncate: FILE" cut the last 64 bytes off WORKDIR/FILE (a damaged
  #                     checkpoint);
  #  "# identical: A B" WORKDIR/A and WORKDIR/B must be the same, byte for
  #                     byte (e.g. the statistics of two runs on different
  #                     numbers of threads, on the same machine).
  file(STRINGS ${PRM} _steps REGEX "^# (run|truncate|identical):")
  if(NOT _steps)
    set(_steps "# run:")
  endif()
  list(LENGTH _steps _n_steps)
  set(_i 0)
  foreach(_step IN LISTS _steps)
    math(EXPR _i "${_i} + 1")
    if(_step MATCHES "^# truncate:[ ]*(.*)$")
      execute_process(COMMAND truncate -s -64 ${WORKDIR}/${CMAKE_MATCH_1}
        RESULT_VARIABLE _rc)
      if(NOT _rc EQUAL 0)
        message(FATAL_ERROR "${_name}: could not truncate ${CMAKE_MATCH_1}")
      endif()
      continue()
    endif()
    if(_step MATCHES "^# identical:[ ]*([^ ]+)[ ]+([^ ]+)[ ]*$")
      execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
        ${WORKDIR}/${CMAKE_MATCH_1} ${WORKDIR}/${CMAKE_MATCH_2}
        RESULT_VARIABLE _rc)
      if(NOT _rc EQUAL 0)
        message(FATAL_ERROR "${_name}: ${CMAKE_MATCH_1} and ${CMAKE_MATCH_2} differ")
      endif()
      continue()
    endif()
    string(REGEX REPLACE "^# run:[ ]*" "" _extra "${_step}")
    # %WORKDIR%: the test's folder (e.g. a file an earlier run wrote).
    string(REPLACE "%WORKDIR%" "${WORKDIR}" _extra "${_extra}")
    separate_arguments(_extra UNIX_COMMAND "${_extra}")
    execute_process(
      COMMAND ${_launcher} ${MPM} ${_files} --set "Output/Directory=${WORKDIR}" --threads ${_threads} ${_extra}
      WORKING_DIRECTORY ${WORKDIR}
      RESULT_VARIABLE _rc
      OUTPUT_FILE ${WORKDIR}/screen.txt
      ERROR_VARIABLE _stderr)
    if(_i LESS _n_steps AND NOT _rc EQUAL 0)
      message(FATAL_ERROR "${_name}: step ${_i} (${_step}) exited with ${_rc}\n${_stderr}")
    endif()
  endforeach()
  if(_name MATCHES "^(bad_input|error)_")
    if(_rc EQUAL 0)
      message(FATAL_ERROR "${_name}: expected a non-zero exit code, got 0")
    endif()
    # Normalise: the work directory differs from machine to machine.
    string(REPLACE "${WORKDIR}" "WORKDIR" _stderr "${_stderr}")
    string(REPLACE "${_prm_dir}/" "" _stderr "${_stderr}")
    file(WRITE ${WORKDIR}/report.txt "exit code ${_rc}\n${_stderr}")
  else()
    if(NOT _rc EQUAL 0)
      file(READ ${WORKDIR}/screen.txt _screen)
      message(FATAL_ERROR "${_name}: mpm exited with ${_rc}\n${_screen}\n${_stderr}")
    endif()
  endif()
  set(_result ${WORKDIR}/report.txt)
else()
  execute_process(
    COMMAND ${EXECUTABLE} ${ARGS}
    WORKING_DIRECTORY ${WORKDIR}
    RESULT_VARIABLE _rc
    OUTPUT_FILE ${WORKDIR}/output.txt
    ERROR_VARIABLE _stderr)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "${_name}: exited with ${_rc}\n${_stderr}")
  endif()
  set(_result ${WORKDIR}/output.txt)
endif()

if(NOT EXISTS ${EXPECTED})
  file(READ ${_result} _got)
  message(FATAL_ERROR "${_name}: no expected output ${EXPECTED}; this run gave:\n${_got}")
endif()
execute_process(
  COMMAND ${NUMDIFF} -q ${_numdiff_options} ${_result} ${EXPECTED}
  RESULT_VARIABLE _diff_rc
  OUTPUT_VARIABLE _diff_out)
if(NOT _diff_rc EQUAL 0)
  execute_process(COMMAND ${NUMDIFF} ${_numdiff_options} ${_result} ${EXPECTED}
    OUTPUT_VARIABLE _diff_out)
  message(FATAL_ERROR "${_name}: output differs from ${EXPECTED} (numdiff ${_numdiff_options}):\n${_diff_out}")
endif()
message(STATUS "${_name}: output matches (numdiff ${_numdiff_options})")
