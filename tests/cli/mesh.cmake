# `pdd mesh` as a user meets it: records sorted by (a, b) with a and b, the summary, the VTK
# file; exit 1 with the element named when an element is skipped; exit 2 for an unreadable
# mesh (message names the line) and for a wrong command line.
set(M ${FIXTURES}/meshes)
function(expect_exit code out_var)
  execute_process(COMMAND ${PDD} mesh --quiet ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL ${code})
    message(FATAL_ERROR "pdd mesh ${ARGN}: exit ${rc}, expected ${code}\n${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${out_var}_err "${err}" PARENT_SCOPE)
endfunction()

file(MAKE_DIRECTORY ${WORK})
expect_exit(0 out --a ${M}/sphere-a.msh --b ${M}/sphere-b.msh --summary --vtk ${WORK}/spheres.vtk)
string(REGEX MATCHALL "\n" lines "${out}")
list(LENGTH lines n)
if(n LESS 1000 OR NOT out MATCHES "^{\"a\":[0-9]+,\"b\":[0-9]+,\"intersecting\":true,\"rigid_pd2\":")
  message(FATAL_ERROR "unexpected records (${n}):\n${out}")
endif()
if(NOT out_err MATCHES "\n  intersecting      ${n} pairs\n" OR NOT out_err MATCHES "\n  pdd2  +[0-9.e+-]+  +[0-9.e+-]+  \\([0-9]+, [0-9]+\\)\n"
   OR NOT out_err MATCHES "\n  value                      sum           max  at \\(a, b\\)\n")
  message(FATAL_ERROR "summary:\n${out_err}")
endif()
if(out MATCHES "_global" OR out_err MATCHES "pdd2_global")  # definitions §9: only when asked for
  message(FATAL_ERROR "default variants wrote pdd2_global keys:\n${out_err}")
endif()

# --variants global (definitions §9): the keys of `pdd solve` after "error", in its order, and
# nothing of the other variants; the summary's sum and maximum.
expect_exit(0 glob --a ${M}/tiny-a.msh --b ${M}/tiny-b.msh --variants global --summary)
string(REGEX MATCHALL "\n" lines "${glob}")
list(LENGTH lines n)
set(num "-?[0-9.e+-]+")
set(vec "\\[${num},${num},${num}\\]")
set(pos "\\[${vec},${vec},${vec},${vec}\\]")
string(REGEX MATCHALL "{\"a\":[0-9]+,\"b\":[0-9]+,\"intersecting\":true,\"error\":null,\"pdd2_global\":${num},\"pdd2_global_normal\":${vec},\"q1_A_global\":${pos},\"q1_B_global\":${pos},\"pdd2_global_error\":null}\n" good "${glob}")
list(LENGTH good g)
if(NOT n EQUAL 51 OR NOT g EQUAL 51 OR glob MATCHES "rigid|pdd2_static|\"pdd2\"|pdd2_global_lower")
  message(FATAL_ERROR "--variants global: ${g} of ${n} records as expected:\n${glob}")
endif()
if(NOT glob_err MATCHES "variants global\\)\n" OR NOT glob_err MATCHES "\n  pdd2_global  +[0-9.e+-]+  +[0-9.e+-]+  \\([0-9]+, [0-9]+\\)\n")
  message(FATAL_ERROR "--variants global summary:\n${glob_err}")
endif()
expect_exit(2 out --a ${M}/tiny-a.msh --b ${M}/tiny-b.msh --variants bogus)
if(NOT out_err MATCHES "--variants: unknown variant 'bogus' \\(rigid, eq11, static, pdd2, relaxed, accel1, accel6, global, all\\)")
  message(FATAL_ERROR "--variants bogus:\n${out_err}")
endif()
if(NOT EXISTS ${WORK}/spheres.vtk)
  message(FATAL_ERROR "no VTK file written")
endif()

# The summary stream: standard output unless the records are there. With --output the records
# go to the file, the summary to standard output and nothing of it to standard error.
expect_exit(0 sum --a ${M}/tiny-a.msh --b ${M}/tiny-b.msh --summary --output ${WORK}/tiny.jsonl)
file(READ ${WORK}/tiny.jsonl tiny_records)
if(NOT sum MATCHES "^pdd mesh: A against B" OR NOT sum MATCHES "\n  value  +sum  +max  at \\(a, b\\)\n"
   OR sum MATCHES "\"a\":" OR sum_err MATCHES "value  +sum" OR NOT tiny_records MATCHES "^{\"a\":")
  message(FATAL_ERROR "--summary with --output: stdout\n${sum}\nstderr\n${sum_err}")
endif()
if(EXISTS /dev/full)  # the summary cannot be written after the records were: exit 2, files named
  execute_process(COMMAND ${PDD} mesh --quiet --a ${M}/tiny-a.msh --b ${M}/tiny-b.msh --summary
                          --output ${WORK}/tiny.jsonl
                  RESULT_VARIABLE rc OUTPUT_FILE /dev/full ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "the summary \\(--summary\\) could not be written: [^\n]*; '[^']*/tiny.jsonl' written, complete\n")
    message(FATAL_ERROR "--summary > /dev/full: exit ${rc}\n${err}")
  endif()
endif()

# --help names the default engine and the summary's stream.
expect_exit(0 help --help)
if(NOT help MATCHES "'fast' \\(doubles[^)]*; the default here, as in Python\\)"
   OR NOT help MATCHES "on standard output with --output, else on standard error")
  message(FATAL_ERROR "pdd mesh --help:\n${help}")
endif()

expect_exit(0 self --a ${M}/two-spheres.msh --self --variants rigid,accel1)
if(NOT self MATCHES "\"pdd2_accel1\"" OR self MATCHES "\"pdd2\"")
  message(FATAL_ERROR "--variants rigid,accel1:\n${self}")
endif()

expect_exit(0 none --a ${M}/conforming-a.msh --b ${M}/conforming-b.msh)
if(NOT none STREQUAL "")
  message(FATAL_ERROR "conforming meshes reported pairs:\n${none}")
endif()

expect_exit(1 flat --a ${M}/bad/flat.msh --b ${M}/sphere-a.msh)
if(NOT flat_err MATCHES "skipped element 1 of mesh A is flat" OR flat STREQUAL "")
  message(FATAL_ERROR "flat element:\n${flat_err}")
endif()

expect_exit(2 out --a ${M}/bad/missing-node.msh --b ${M}/sphere-a.msh)
if(NOT out_err MATCHES "missing-node.msh:14: element 2 \\(tetrahedron 1\\) refers to node 7")
  message(FATAL_ERROR "missing node:\n${out_err}")
endif()
expect_exit(2 out --a ${M}/bad/truncated.msh --b ${M}/sphere-a.msh)
expect_exit(2 out --a ${M}/sphere-a.msh --b ${M}/sphere-b.msh --self)
expect_exit(2 out --a ${M}/sphere-a.msh)
expect_exit(2 out --a ${M}/sphere-a.msh --b ${M}/sphere-b.msh --variants rigid,nonsense)
expect_exit(2 out --a ${M}/sphere-a.msh --b ${M}/sphere-b.msh --output ${WORK}/no/such/dir/x.jsonl)

# A mesh with no first-order tetrahedra (surface triangles only; a second-order tetrahedron,
# Gmsh type 11; VTK hexahedra) is an error that says so, not an empty result.
file(WRITE ${WORK}/surface.msh "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n2\n1 2 0 1 2 3\n2 2 0 1 2 4\n$EndElements\n")
file(WRITE ${WORK}/tet10.msh "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 .5 0 0\n6 .5 .5 0\n7 0 .5 0\n8 0 0 .5\n9 0 .5 .5\n10 .5 0 .5\n$EndNodes\n$Elements\n1\n1 11 0 1 2 3 4 5 6 7 8 9 10\n$EndElements\n")
file(WRITE ${WORK}/hex.vtk "# vtk DataFile Version 3.0\nhex\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\nCELLS 1 9\n8 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n12\n")
# Coordinates are doubles, in every reader (the fixture reader's rule, io/fixture_io.cpp): an
# integer literal that is not exactly a double (2^53 + 1, a 30-digit integer, 10^400) is an
# error naming the file, the line and the integer; 2^53 and 10^20 = 2^20 5^20 are doubles and
# are read as they are, and so is 2^53 + 1 written with an exponent (the nearest double).
set(tet "1 0 0 0\n2 4 0 0\n3 0 4 0\n")
foreach(bad "9007199254740993" "-123456789012345678901234567890" "1000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000")
  file(WRITE ${WORK}/int.msh "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n${tet}4 0 0 ${bad}\n$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n")
  file(WRITE ${WORK}/int.vtk "# vtk DataFile Version 3.0\nint\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 4 0 0\n0 4 0 0 0 ${bad}\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n")
  string(SUBSTRING "${bad}" 0 30 shown)
  foreach(f int.msh:9 int.vtk:7)
    string(REGEX REPLACE ":.*" "" file "${f}")
    expect_exit(2 out --a ${WORK}/${file} --b ${M}/tiny-b.msh)
    if(NOT out_err MATCHES "${f}: a [a-z]+ coordinate: the integer ${shown}[0-9.]* is (not exactly a double|beyond the largest double)" OR NOT out STREQUAL "")
      message(FATAL_ERROR "integer ${bad} in ${file}:\n${out_err}")
    endif()
  endforeach()
endforeach()
foreach(good "9007199254740992" "100000000000000000000" "9007199254740993e0" "-0")
  file(WRITE ${WORK}/int.msh "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n${tet}4 0 0 ${good}\n$EndNodes\n$Elements\n1\n1 4 0 1 2 3 4\n$EndElements\n")
  execute_process(COMMAND ${PDD} mesh --quiet --a ${WORK}/int.msh --b ${M}/tiny-b.msh RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(err MATCHES "integer")  # -0: a flat element (exit 1), read all the same
    message(FATAL_ERROR "integer ${good} refused:\n${err}")
  endif()
endforeach()

foreach(f surface.msh tet10.msh hex.vtk)
  expect_exit(2 out --a ${WORK}/${f} --b ${M}/tiny-b.msh)
  if(NOT out_err MATCHES "${f}: no first-order tetrahedra" OR NOT out STREQUAL "")
    message(FATAL_ERROR "a mesh without tetrahedra (${f}):\n${out_err}\n${out}")
  endif()
endforeach()
