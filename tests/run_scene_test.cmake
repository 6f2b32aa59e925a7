# Runs one scene test (called by ctest through 'cmake -P'):
#  1. copies the .prm (and auxiliary files) into a fresh working directory,
#  2. runs sluice on it, on NP MPI ranks when NP > 1,
#  3. checks the exit code against EXPECT_EXIT,
#  4. keeps the lines of standard output matching FILTER (or, for a run expected
#     to fail, standard error), drops the wall times, writes them to 'compared_output',
#  5. compares them with the reference using numdiff and NUMDIFF_ARGS,
#  6. with CHECK_NO_OUTPUT, checks that the failed run created and changed nothing;
#     for a run that stopped later (exit 4 or 5), that what it wrote is whole:
#     every .pvd index closed, every .csv row complete, and every file the
#     message names as holding the state at the stop there, each .pvd's last
#     entry with it.
# WITH_STDERR compares standard error too for a run expected to succeed (warnings).
foreach(var SLUICE PRM REFERENCE WORK_DIR NUMDIFF NP EXPECT_EXIT FILTER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_scene_test.cmake: ${var} is not set")
  endif()
endforeach()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
get_filename_component(prm_name ${PRM} NAME)
file(COPY ${PRM} DESTINATION ${WORK_DIR})
if(DEFINED AUX_FILES)
  string(REPLACE "|" ";" aux "${AUX_FILES}")
  foreach(f ${aux})
    file(COPY ${f} DESTINATION ${WORK_DIR})
  endforeach()
endif()

# A failing run must leave an existing output directory as it was.
if(CHECK_NO_OUTPUT)
  file(WRITE ${WORK_DIR}/output/particles.pvd "sentinel")
endif()

if(NP GREATER 1)
  set(command ${MPIEXEC} -np ${NP} --oversubscribe ${SLUICE} ${prm_name})
else()
  set(command ${SLUICE} ${prm_name})
endif()
execute_process(COMMAND ${command}
  WORKING_DIRECTORY ${WORK_DIR}
  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
file(WRITE ${WORK_DIR}/stdout "${out}")
file(WRITE ${WORK_DIR}/stderr "${err}")

if(NOT "${rc}" STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECT_EXIT}\n--- stdout:\n${out}\n--- stderr:\n${err}")
endif()

if(CHECK_NO_OUTPUT)
  file(GLOB created RELATIVE ${WORK_DIR}/output ${WORK_DIR}/output/*)
  file(READ ${WORK_DIR}/output/particles.pvd sentinel)
  if(NOT "${created}" STREQUAL "particles.pvd" OR NOT "${sentinel}" STREQUAL "sentinel")
    message(FATAL_ERROR "the failed run wrote output: ${created}")
  endif()
  file(GLOB stray RELATIVE ${WORK_DIR} ${WORK_DIR}/*)
  list(REMOVE_ITEM stray ${prm_name} output stdout stderr compared_output)
  foreach(f ${aux})
    get_filename_component(aux_name ${f} NAME)
    list(REMOVE_ITEM stray ${aux_name})
  endforeach()
  if(stray)
    message(FATAL_ERROR "the failed run created files: ${stray}")
  endif()
endif()
if(DEFINED ABSENT_FILES AND NOT "${ABSENT_FILES}" STREQUAL "")
  string(REPLACE "|" ";" absent "${ABSENT_FILES}")
  foreach(f ${absent})
    if(EXISTS ${WORK_DIR}/${f})
      message(FATAL_ERROR "${f} should not exist after the run")
    endif()
  endforeach()
endif()

# A run that stopped part-way must leave readable output behind.
if(EXPECT_EXIT EQUAL 4 OR EXPECT_EXIT EQUAL 5)
  if(err MATCHES "the state at the stop \\(t = [^)]*\\) is the last entry of ([^\n]*)")
    string(REPLACE " and " ", " named "${CMAKE_MATCH_1}")
    string(REPLACE ", " ";" named "${named}")
    foreach(f ${named})
      if(NOT EXISTS ${WORK_DIR}/${f})
        message(FATAL_ERROR "the stopped run names ${f} for its state at the stop; it is missing")
      endif()
      if(f MATCHES "\\.pvd$")
        file(STRINGS ${WORK_DIR}/${f} entries REGEX "file=\"[^\"]*\"")
        list(GET entries -1 last)
        string(REGEX REPLACE ".*file=\"([^\"]*)\".*" "\\1" last "${last}")
        get_filename_component(pvd_dir ${WORK_DIR}/${f} DIRECTORY)
        if(NOT EXISTS ${pvd_dir}/${last})
          message(FATAL_ERROR "the last entry of ${f}, ${last}, is missing")
        endif()
      endif()
    endforeach()
  endif()
  file(GLOB_RECURSE pvd_files ${WORK_DIR}/*.pvd)
  foreach(f ${pvd_files})
    file(READ ${f} content)
    if(NOT content MATCHES "</VTKFile>[ \n]*$")
      message(FATAL_ERROR "the stopped run left an unclosed series index ${f}")
    endif()
  endforeach()
  file(GLOB_RECURSE csv_files ${WORK_DIR}/*.csv)
  foreach(f ${csv_files})
    file(STRINGS ${f} rows REGEX "^[^#]") # (a particle dump starts with a "# time" line)
    list(GET rows 0 header)
    string(REGEX REPLACE "[^,]" "" header_commas "${header}")
    foreach(row ${rows})
      string(REGEX REPLACE "[^,]" "" commas "${row}")
      if(NOT commas STREQUAL header_commas)
        message(FATAL_ERROR "the stopped run left an incomplete row in ${f}: '${row}'")
      endif()
    endforeach()
    file(READ ${f} content)
    if(NOT content MATCHES "\n$")
      message(FATAL_ERROR "the stopped run left ${f} without a final newline")
    endif()
  endforeach()
endif()

# A run that is meant to fail is judged by what it says on standard error.
if(EXPECT_EXIT EQUAL 0 AND WITH_STDERR)
  set(text "${out}${err}")
elseif(EXPECT_EXIT EQUAL 0)
  set(text "${out}")
else()
  set(text "${err}")
endif()

# Keep the deterministic lines; wall times differ from run to run.
# (Semicolons would split CMake list items, and an unmatched bracket would keep
# them from splitting: protect both while splitting lines.)
string(REPLACE ";" "<semicolon>" text "${text}")
string(REPLACE "[" "<lbracket>" text "${text}")
string(REPLACE "]" "<rbracket>" text "${text}")
string(REPLACE "\n" ";" lines "${text}")
set(kept "")
foreach(line IN LISTS lines)
  if(line MATCHES "${FILTER}")
    string(REGEX REPLACE " wall_s=[^ ]*" "" line "${line}")
    string(REPLACE "<semicolon>" ";" line "${line}")
    string(REPLACE "<lbracket>" "[" line "${line}")
    string(REPLACE "<rbracket>" "]" line "${line}")
    string(APPEND kept "${line}\n")
  endif()
endforeach()
file(WRITE ${WORK_DIR}/compared_output "${kept}")
# A comparison of nothing cannot fail: refuse it.
if("${kept}" STREQUAL "")
  message(FATAL_ERROR "no line of the output matches the filter '${FILTER}'\n--- stdout:\n${out}\n--- stderr:\n${err}")
endif()

separate_arguments(numdiff_args UNIX_COMMAND "${NUMDIFF_ARGS}")
execute_process(COMMAND ${NUMDIFF} ${numdiff_args}
  -s " \t\n=,:;()'" ${REFERENCE} ${WORK_DIR}/compared_output
  OUTPUT_VARIABLE diff RESULT_VARIABLE diff_rc)
if(NOT diff_rc EQUAL 0)
  message(FATAL_ERROR "output differs from ${REFERENCE}:\n${diff}\n--- output:\n${kept}")
endif()
