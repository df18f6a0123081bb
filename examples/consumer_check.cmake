# consumer_check.cmake — install BUILD to WORK/prefix, build the consumer project SRC against
# it with find_package(pdd CONFIG REQUIRED) only, run it, and check what it prints.
# Expected values: fixtures/golden/smoke.jsonl, pair "poke-vertex-through-face".
file(REMOVE_RECURSE ${WORK})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
run(${CMAKE_COMMAND} -S ${SRC} -B ${WORK}/build -DCMAKE_PREFIX_PATH=${WORK}/prefix
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK}/build)
run(${WORK}/build/consumer)
message(STATUS "consumer printed:\n${out}")
foreach(line "exact: pdd2 = 3/224 along FV:3" "fast:  pdd2 = 0.0133929 along FV:3"
             "rigid: pd2 = 0.25 along FV:3 (exact 1/4)"
             "mesh:  1 pair, pdd2 = 0.0133929; self-contact of A: 0 pairs")
  string(FIND "${out}" "${line}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "consumer output lacks \"${line}\"")
  endif()
endforeach()
# Only the public headers (pdd.h, global_minimiser.h; mesh.h and the per-concept headers of pdd/mesh/ it includes)
# and the plain types they include are installed.
file(GLOB_RECURSE headers RELATIVE ${WORK}/prefix/include ${WORK}/prefix/include/*)
list(SORT headers)
set(expected pdd/direction_label.h pdd/global_minimiser.h pdd/mesh.h pdd/mesh/broadphase.h pdd/mesh/check_resolution.h
    pdd/mesh/contact_energy.h pdd/mesh/contacts.h pdd/mesh/mesh.h pdd/mesh/resolve.h pdd/mesh/variants.h
    pdd/mesh/vtk.h pdd/mesh/write_mesh.h pdd/pair_result.h pdd/pdd.h pdd/qp_formulation.h
    pdd/solve_options.h
    pdd/tet_pair.h pdd/tet_tables.h)
if(NOT headers STREQUAL expected)
  message(FATAL_ERROR "installed headers: ${headers}; expected ${expected}")
endif()
