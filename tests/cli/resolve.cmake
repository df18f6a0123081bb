# `pdd resolve` as a user meets it, on the shipped meshes (fixtures/meshes):
#   exit 0: the two tiny cubes (51 intersecting pairs) with A fixed, and the same two as one
#           mesh (--self) are resolved; the report says R1-R3 hold and lists nothing; `pdd mesh` on the written
#           meshes finds no intersecting pair (an independent check of R1 through the contacts
#           pipeline); resolving the result again moves nothing, so A's output is the same file
#           as A itself written unchanged (bit for bit: the writer prints every double in its
#           shortest round-trip form, so equal files <=> equal doubles);
#   exit 1: an input with a flat element (skipped, named, not covered by the checks);
#           the shipped balls (0.73 deep, about 2.4 element layers) with --max-rounds 1 are not resolved: the
#           meshes and the report are still written, standard error names what remains;
#   exit 2: every wrong command line, a missing mesh, an unwritable output — with a message,
#           nothing computed (no progress line) and nothing written (no output, no temporary).
set(M ${FIXTURES}/meshes)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(run_resolve code out_var)
  execute_process(COMMAND ${PDD} resolve ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL ${code})
    message(FATAL_ERROR "pdd resolve ${ARGN}: exit ${rc}, expected ${code}\n${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${out_var}_err "${err}" PARENT_SCOPE)
endfunction()

# The report's verdict keys; `expect` TRUE: resolved with nothing remaining.
function(check_report path expect)
  file(READ ${path} json)
  foreach(key variant method stopped_because inputs resolved r1 r2 r3 r4 rounds cost cost_a cost_b max_displacement
          min_volume_ratio max_volume_ratio min_shape_ratio volume_ratio_histogram
          shape_ratio_histogram worst_elements remaining_pairs bad_elements poor_elements
          moved_fixed_vertices skipped
          seconds_contacts seconds_solve seconds_move seconds_verify seconds_total)
    string(JSON ignored ERROR_VARIABLE missing GET "${json}" ${key})
    if(missing)
      message(FATAL_ERROR "${path}: no key '${key}'")
    endif()
  endforeach()
  string(JSON resolved GET "${json}" resolved)
  string(JSON remaining LENGTH "${json}" remaining_pairs)
  string(JSON bad LENGTH "${json}" bad_elements)
  string(JSON moved LENGTH "${json}" moved_fixed_vertices)
  string(JSON poor LENGTH "${json}" poor_elements)
  if(expect)
    if(NOT resolved OR NOT remaining EQUAL 0 OR NOT bad EQUAL 0 OR NOT moved EQUAL 0 OR NOT poor EQUAL 0)
      message(FATAL_ERROR "${path}: not resolved as expected:\n${json}")
    endif()
    foreach(r r1 r2 r3 r4)
      string(JSON v GET "${json}" ${r})
      if(NOT v)
        message(FATAL_ERROR "${path}: ${r} false in a resolved report")
      endif()
    endforeach()
  elseif(resolved OR (remaining EQUAL 0 AND bad EQUAL 0 AND poor EQUAL 0))
    message(FATAL_ERROR "${path}: reported resolved, or unresolved with nothing remaining:\n${json}")
  endif()
endfunction()

# No file in WORK but `allowed` (a failed run leaves no output and no temporary file).
function(expect_only allowed)
  file(GLOB present RELATIVE ${WORK} ${WORK}/*)
  foreach(f ${present})
    list(FIND allowed ${f} at)
    if(at EQUAL -1)
      message(FATAL_ERROR "unexpected file left in ${WORK}: ${f}")
    endif()
  endforeach()
endfunction()

# --- exit 2: wrong command lines and unwritable outputs: nothing computed, nothing written.
set(W ${WORK})
set(A --a ${M}/sphere-a.msh)
set(AB --a ${M}/sphere-a.msh --b ${M}/sphere-b.msh)
set(OUT --out-a ${W}/a1.msh --out-b ${W}/b1.msh --report ${W}/r.json --vtk ${W}/both.vtk)
foreach(case
    "--a;${M}/no-such.msh;--b;${M}/sphere-b.msh;--out-a;${W}/a1.msh;--out-b;${W}/b1.msh|no-such.msh"
    "${AB};${OUT};--fix;c|--fix: c not in \\{a,b\\}"
    "${AB};--self;${OUT}|give either --b B or --self"
    "${A};--out-a;${W}/a1.msh|give either --b B or --self"
    "${AB};--out-a;${W}/a1.msh|--out-b is missing"
    "${A};--self;--out-a;${W}/a1.msh;--out-b;${W}/b1.msh|--out-b: with --self there is no mesh B"
    "${A};--self;--fix;b;--out-a;${W}/a1.msh|--fix b: with --self there is no mesh B"
    "${AB};--out-a;${W}/a1.obj;--out-b;${W}/b1.msh|--out-a '${W}/a1.obj': unknown extension"
    "${AB};${OUT};--variant;bogus|--variant: bogus not in"
    "${AB};${OUT};--max-rounds;0|--max-rounds: 0 is out of range"
    "${AB};${OUT};--min-volume-ratio;0|--min-volume-ratio: must be a number in \\(0, 1\\]; got 0"
    "${AB};${OUT};--min-shape-ratio;1.5|--min-shape-ratio: must be a number in \\(0, 1\\]; got 1.5"
    "${AB};${OUT};--min-shape-ratio;half|--min-shape-ratio: must be a number in \\(0, 1\\]; got half"
    "${AB};--out-a;${M}/sphere-a.msh;--out-b;${W}/b1.msh|--out-a '.*sphere-a.msh' is the same file as --a"
    "${AB};--out-a;${W}/a1.msh;--out-b;${W}/a1.msh|--out-b '.*a1.msh' is the same file as --out-a"
    "${AB};--out-a;${W}/a1.msh;--out-b;${W}/b1.msh;--report;${W}/no/such/dir/r.json|--report: cannot write '.*r.json': No such file or directory \\(nothing computed, nothing written\\)"
    "${AB};--out-a;${W}/no/such/dir/a1.vtk;--out-b;${W}/b1.msh|--out-a: cannot write"
    "${AB};--out-a;${W}/a1.msh;--out-b;${W}/b1.msh;--vtk;${W}|--vtk: cannot write")
  string(REPLACE "|" ";" parts "${case}")
  list(POP_BACK parts message)
  run_resolve(2 out ${parts})
  if(NOT out_err MATCHES "${message}")
    message(FATAL_ERROR "pdd resolve ${parts}: expected a message matching '${message}', got:\n${out_err}")
  endif()
  if(out_err MATCHES "round [0-9]+:")
    message(FATAL_ERROR "pdd resolve ${parts}: computed before failing:\n${out_err}")
  endif()
  expect_only("")
endforeach()
# A mesh that cannot be read: the reader's message, with the line.
run_resolve(2 out --a ${M}/bad/missing-node.msh --b ${M}/sphere-b.msh ${OUT})
if(NOT out_err MATCHES "missing-node.msh:14: element 2 \\(tetrahedron 1\\) refers to node 7")
  message(FATAL_ERROR "unreadable mesh:\n${out_err}")
endif()
expect_only("")

# --- exit 0: the tiny cubes, A fixed; meshes as .msh (A) and .vtk (B), report, ParaView file.
set(TINY --a ${M}/tiny-a.msh --b ${M}/tiny-b.msh)
run_resolve(0 sum ${TINY} --fix a --out-a ${W}/a1.msh --out-b ${W}/b1.vtk --report ${W}/r.json
            --vtk ${W}/both.vtk --summary)
check_report(${W}/r.json TRUE)
if(NOT sum MATCHES "^pdd resolve: resolved after [0-9]+ rounds? \\(variant global, method [a-z ]+, A against B\\)\n"
   OR NOT sum MATCHES "\n  mesh A            .*tiny-a.msh: [0-9]+ tetrahedra, [0-9]+ vertices, all fixed\n"
   OR NOT sum MATCHES "\n  R1 no overlap     yes"
   OR NOT sum MATCHES "\n  R2 no inversion   yes"
   OR NOT sum MATCHES "\n  R3 fixed kept     yes"
   OR NOT sum MATCHES "\n  R4 usable         yes: every element V1/V0 in \\[0.25, 1/0.25\\], eta1/eta0 >= 0.5"
   OR NOT sum MATCHES "\n  min shape ratio   [0-9.e+-]+"
   OR NOT sum MATCHES "\n  volume ratios     < 0: 0, "
   OR NOT sum MATCHES "\n  worst elements    [AB] [0-9]+ "
   OR NOT sum MATCHES "\n  cost              [0-9.e+-]+  \\(A 0, B [0-9.e+-]+\\)"
   OR NOT sum MATCHES "\n                     round    pairs       max pd2          cost    seconds\n")
  message(FATAL_ERROR "--summary:\n${sum}")
endif()
if(NOT sum_err MATCHES "pdd resolve: round 1: [0-9]+ intersecting pairs"
   OR NOT sum_err MATCHES "pdd resolve: resolved in [0-9]+ rounds? ")
  message(FATAL_ERROR "progress lines:\n${sum_err}")
endif()
expect_only("a1.msh;b1.vtk;r.json;both.vtk")
file(READ ${W}/both.vtk vtk)
if(NOT vtk MATCHES "VECTORS displacement double\n")
  message(FATAL_ERROR "both.vtk has no displacement field")
endif()
# R1 independently: the contacts pipeline finds no pair between the written meshes.
execute_process(COMMAND ${PDD} mesh --quiet --a ${W}/a1.msh --b ${W}/b1.vtk
                RESULT_VARIABLE rc OUTPUT_VARIABLE pairs ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT pairs STREQUAL "")
  message(FATAL_ERROR "pdd mesh on the resolved meshes: exit ${rc}\n${pairs}${err}")
endif()
# Resolving the result again takes no round and moves nothing: a2 is A written unchanged,
# b2 is b1 (bit for bit, as files).
run_resolve(0 again --a ${M}/tiny-a.msh --b ${W}/b1.vtk --out-a ${W}/a2.msh --out-b ${W}/b2.vtk
            --report ${W}/r2.json --quiet)
file(READ ${W}/r2.json r2)
string(JSON rounds LENGTH "${r2}" rounds)
string(JSON cost GET "${r2}" cost)
if(NOT rounds EQUAL 0 OR NOT cost EQUAL 0 OR NOT again_err STREQUAL "")
  message(FATAL_ERROR "resolving a resolved pair: ${rounds} rounds, cost ${cost}\n${again_err}")
endif()
foreach(pair "a1.msh;a2.msh" "b1.vtk;b2.vtk")
  list(GET pair 0 x)
  list(GET pair 1 y)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${W}/${x} ${W}/${y} RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${x} and ${y} differ: the fixed (or already resolved) mesh moved")
  endif()
endforeach()

# A write that fails after the computation (/dev/full takes no data): exit 2, and the meshes
# already written to their temporary names are removed; /dev/full is still the device.
file(REMOVE_RECURSE ${W})
file(MAKE_DIRECTORY ${W})
if(EXISTS /dev/full)
  run_resolve(2 full ${TINY} --out-a ${W}/a1.msh --out-b ${W}/b1.msh --report /dev/full --quiet)
  if(NOT full_err MATCHES "cannot write to '/dev/full': No space left on device \\(nothing written\\)")
    message(FATAL_ERROR "--report /dev/full:\n${full_err}")
  endif()
  expect_only("")
  if(NOT EXISTS /dev/full OR IS_DIRECTORY /dev/full)
    message(FATAL_ERROR "/dev/full replaced")
  endif()
  execute_process(COMMAND stat -c %F /dev/full OUTPUT_VARIABLE kind)
  if(NOT kind MATCHES "character special file")
    message(FATAL_ERROR "/dev/full is now: ${kind}")
  endif()
endif()

# The summary (standard output) cannot be written, after the meshes were: exit 2 (an output
# could not be written), and the message says which part failed and that the meshes are whole.
if(EXISTS /dev/full)
  file(REMOVE_RECURSE ${W})
  file(MAKE_DIRECTORY ${W})
  execute_process(COMMAND ${PDD} resolve ${TINY} --out-a ${W}/a1.msh --out-b ${W}/b1.msh --summary --quiet
                  OUTPUT_FILE /dev/full RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "the summary \\(--summary\\) could not be written: cannot write to standard output[^\n]*; '[^']*/a1.msh', '[^']*/b1.msh' are written, each complete\n")
    message(FATAL_ERROR "--summary > /dev/full: exit ${rc}\n${err}")
  endif()
  foreach(f a1.msh b1.msh)
    execute_process(COMMAND ${PDD} mesh --quiet --a ${W}/${f} --self --variants rigid RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${f}, written before the summary failed, does not read back:\n${err}")
    endif()
  endforeach()
endif()

# A flat element in the input: skipped, named, and the run exits 1 even when the rest is
# resolved (no check covers that element), as `pdd mesh` does.
run_resolve(1 flat --a ${M}/bad/flat.msh --b ${M}/tiny-b.msh --out-a ${W}/f1.msh --out-b ${W}/f2.msh --quiet --summary)
if(NOT flat_err MATCHES "skipped element 1 of mesh A is flat: its four vertices are coplanar \\(volume 0\\)\n"
   OR NOT flat_err MATCHES "1 input elements were skipped \\(named above\\): the checks do not cover them\n"
   OR NOT flat MATCHES "\n  R2 no inversion   yes: .* \\(not the 1 skipped elements\\)\n")
  message(FATAL_ERROR "flat element:\n${flat}${flat_err}")
endif()

# --- exit 0: self-contact: the two cubes as one mesh of two components (`pdd mesh --vtk` writes
# A's points and cells, then B's), whose pairs that share no vertex are the A x B pairs and
# pairs within one cube (none intersect).
execute_process(COMMAND ${PDD} mesh --quiet ${TINY} --vtk ${W}/tiny-both.vtk --output ${W}/pairs.jsonl
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pdd mesh --vtk on the tiny cubes: exit ${rc}")
endif()
run_resolve(0 self --a ${W}/tiny-both.vtk --self --out-a ${W}/self.vtk --report ${W}/self.json --quiet)
check_report(${W}/self.json TRUE)
execute_process(COMMAND ${PDD} mesh --quiet --a ${W}/self.vtk --self
                RESULT_VARIABLE rc OUTPUT_VARIABLE pairs ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT pairs STREQUAL "")
  message(FATAL_ERROR "pdd mesh --self on the resolved mesh: exit ${rc}\n${pairs}${err}")
endif()

# --- exit 1: the shipped balls, one round: written anyway, what remains named.
file(REMOVE_RECURSE ${W})
file(MAKE_DIRECTORY ${W})
run_resolve(1 deep ${AB} --max-rounds 1 --out-a ${W}/a1.msh
            --out-b ${W}/b1.msh --report ${W}/r.json --quiet --summary)
check_report(${W}/r.json FALSE)
if(NOT deep_err MATCHES "pdd resolve: NOT resolved after 1 round \\(--max-rounds 1\\); the meshes are written as they are\n"
   OR NOT deep_err MATCHES "pdd resolve: [0-9]+ (element pairs \\(a, b\\) still intersect: \\([0-9]+, [0-9]+\\)|elements inverted or flat: [AB] [0-9]+)")
  message(FATAL_ERROR "unresolved run, standard error:\n${deep_err}")
endif()
if(NOT deep MATCHES "^pdd resolve: NOT resolved after 1 round " OR NOT deep MATCHES "\n  rounds            1 of at most 1\n")
  message(FATAL_ERROR "unresolved run, summary:\n${deep}")
endif()
expect_only("a1.msh;b1.msh;r.json")
