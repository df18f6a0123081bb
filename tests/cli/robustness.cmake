# Every `pdd` command on bad input, bad arguments and failed writes: the exit code of
# exit_codes.h (1 some pair rejected, 2 unreadable file / usage error / lost output) and a
# message naming the problem. One check per reported defect; each fails if the defect returns.
# Needs PDD, FIXTURES, WORK (a scratch folder).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# run(<expected exit> <regex the stderr must match> ARGS... [STDOUT file]) — sets `out`, `err`.
function(run code pattern)
  cmake_parse_arguments(R "" "STDOUT;STDIN" "" ${ARGN})
  set(extra)
  if(R_STDOUT)
    list(APPEND extra OUTPUT_FILE ${R_STDOUT})
  else()
    list(APPEND extra OUTPUT_VARIABLE out)
  endif()
  if(R_STDIN)
    list(APPEND extra INPUT_FILE ${R_STDIN})
  endif()
  execute_process(COMMAND ${PDD} ${R_UNPARSED_ARGUMENTS} RESULT_VARIABLE rc ERROR_VARIABLE err ${extra}
                  TIMEOUT 1200)  # generous: the sanitized build (scripts/sanitize.sh) runs this too
  string(REPLACE ";" " " cmd "${R_UNPARSED_ARGUMENTS}")
  if(NOT rc STREQUAL "${code}")
    message(FATAL_ERROR "pdd ${cmd}: exit '${rc}', expected ${code}\n${err}")
  endif()
  if(NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "pdd ${cmd}: stderr does not match '${pattern}':\n${err}")
  endif()
  if(err MATCHES "[0-9]{40}")
    message(FATAL_ERROR "pdd ${cmd}: message with a 40-digit number:\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect_no_output what)
  if(NOT out STREQUAL "")
    message(FATAL_ERROR "${what}: unexpected output\n${out}")
  endif()
endfunction()

set(B ${FIXTURES}/bad)
set(SOLVE solve --engine reference --formulation reduced --quiet)

# ---- 1. the fixture reader ---------------------------------------------------------------
# Overflowing numbers: that pair rejected as non-finite, a numeric name rejected by index,
# a string coordinate is not a number, the rest computed.
foreach(engine reference fast)
  run(1 "pair 'overflow-x' rejected: [^\n]*finite" solve --engine ${engine} --formulation reduced --quiet --input ${B}/overflow.json)
  string(REGEX MATCHALL "\n" lines "${out}")
  list(LENGTH lines n)
  if(NOT n EQUAL 6 OR out MATCHES "pdd:overflow" OR NOT out MATCHES "\"name\":\"#4 \\(byte 342\\)\",\"error\":\"field 'name' must be a string"
     OR NOT out MATCHES "\"name\":\"overflow-negative\",\"error\":\"[^\"]*finite"
     OR NOT out MATCHES "\"name\":\"marker-string\",\"error\":\"[^\"]*coordinate z is not a number"
     OR NOT out MATCHES "\"name\":\"good-after\",\"intersecting\":true")
    message(FATAL_ERROR "overflow.json (${engine}): wrong records\n${out}")
  endif()
endforeach()
foreach(f number-dot-exponent number-two-exponents number-leading-zero)
  run(2 "malformed JSON at byte [0-9]+: '[-0-9.e]+' is not a valid number" ${SOLVE} --input ${B}/${f}.json)
  expect_no_output(${f})
endforeach()
run(2 "duplicate key \"pairs\" at byte 110" ${SOLVE} --input ${B}/duplicate-pairs.json)
expect_no_output(duplicate-pairs)
run(2 "duplicate key \"name\" at byte 28" ${SOLVE} --input ${B}/duplicate-name.json)
run(2 "NUL byte at byte 110" ${SOLVE} --input ${B}/nul-byte.json)
expect_no_output(nul-byte)
run(2 "malformed JSON at byte [0-9]+" ${SOLVE} --input ${B}/trailing-garbage.json)
expect_no_output(trailing-garbage)
run(2 "'${B}': it is a directory" ${SOLVE} --input ${B})
run(2 "cannot open '${B}/does-not-exist.json': No such file or directory" ${SOLVE} --input ${B}/does-not-exist.json)
run(2 "file is empty" ${SOLVE} --input ${B}/empty.json)
# "-" is standard input; an integer coordinate that is not exactly a double rejects its pair only
file(WRITE ${WORK}/ints.json "{\"pairs\":[{\"name\":\"big\",\"A\":[[0,0,0],[9007199254740993,0,0],[0,10,0],[0,0,10]],\"B\":[[1,1,1],[2,1,1],[1,2,1],[1,1,2]]},{\"name\":\"ok\",\"A\":[[0,0,0],[9007199254740992,0,0],[0,10,0],[0,0,10]],\"B\":[[1,1,1],[2,1,1],[1,2,1],[1,1,2]]}]}")
foreach(engine reference fast)
  run(1 "pair 'big' rejected: the integer 9007199254740993 at byte 38 is not exactly a double" solve --engine ${engine} --formulation reduced --quiet --input - STDIN ${WORK}/ints.json)
  if(NOT out MATCHES "\"name\":\"ok\",\"intersecting\":true")
    message(FATAL_ERROR "--input - (${engine}): wrong records\n${out}")
  endif()
endforeach()
run(1 "pair '#2 \\(byte 114\\)' rejected: field 'name' must be a string.*pair 'bad-tags' rejected.*pair '#7 \\(byte 630\\)' rejected: entry is not a JSON object"
    ${SOLVE} --input ${B}/mistyped.json)
if(NOT out MATCHES "\"name\":\"good-after\",\"intersecting\":true")
  message(FATAL_ERROR "mistyped.json: the batch did not go on\n${out}")
endif()
# The other readers of fixture files say the same.
run(2 "duplicate key" compare --input ${B}/duplicate-pairs.json)
run(2 "NUL byte" theorem --input ${B}/nul-byte.json)
run(2 "is a directory" audit-ee --input ${B})

# ---- 2. failed writes are errors -----------------------------------------------------------
# (reduced formulation: the write is what is tested, and the full one is slow under sanitizers)
foreach(engine reference fast)
  run(2 "cannot write to '/dev/full'" solve --engine ${engine} --formulation reduced --quiet --input ${FIXTURES}/smoke.json --output /dev/full)
  run(2 "cannot write to standard output" solve --engine ${engine} --formulation reduced --quiet --input ${FIXTURES}/smoke.json STDOUT /dev/full)
endforeach()
run(2 "cannot write to '/dev/full'" generate --family paper --count 3 --output /dev/full)
run(2 "cannot write to standard output" generate --family paper --count 3 STDOUT /dev/full)
run(2 "cannot write to standard output" compare --input ${FIXTURES}/smoke.json --json STDOUT /dev/full)
run(2 "cannot write to standard output" theorem --input ${FIXTURES}/smoke.json --json --nef 0 STDOUT /dev/full)
run(2 "cannot write to standard output" audit-ee --input ${FIXTURES}/smoke.json --json STDOUT /dev/full)
# golden --update whose golden file is /dev/full
file(MAKE_DIRECTORY ${WORK}/fixtures/golden)
file(COPY ${FIXTURES}/smoke.json DESTINATION ${WORK}/fixtures)
file(CREATE_LINK /dev/full ${WORK}/fixtures/golden/smoke.jsonl SYMBOLIC)
run(2 "pdd golden: cannot write to '.*smoke.jsonl'" golden --update --fixtures ${WORK}/fixtures)
# paper: a picture's data file that cannot be written, the report that cannot be written
file(MAKE_DIRECTORY ${WORK}/paper)
file(CREATE_LINK /dev/full ${WORK}/paper/fig3_histograms.dat SYMBOLIC)
run(2 "pdd paper: cannot write to '.*fig3_histograms.dat'" paper --count 20 --exact-sample 2 --repeats 1 --out ${WORK}/paper)
file(MAKE_DIRECTORY ${WORK}/paper2)
file(CREATE_LINK /dev/full ${WORK}/paper2/report.md SYMBOLIC)
run(2 "pdd paper: cannot write to '.*report.md'" paper --count 20 --exact-sample 2 --repeats 1 --out ${WORK}/paper2)

# ---- 3. numbers on the command line --------------------------------------------------------
run(2 "--count: -1 is out of range" generate --family paper --count -1)
run(2 "--count: '1.5' is not an integer" generate --family paper --count 1.5)
run(2 "--seed: '-1' is not a seed" generate --family paper --seed -1)
run(2 "--seed: 18446744073709551616 is out of range" generate --family paper --seed 18446744073709551616)
run(2 "--seed: 'x' is not a seed" generate --family paper --seed x)
run(0 "" generate --family paper --count 1 --seed 18446744073709551615)
run(2 "--threads: 'x' is not an integer" ${SOLVE} --input ${FIXTURES}/smoke.json --threads x)
run(2 "--threads: -1 is out of range" ${SOLVE} --input ${FIXTURES}/smoke.json --threads -1)
run(2 "--nef: -1 is out of range" theorem --input ${FIXTURES}/smoke.json --nef -1)
run(2 "--count: 0 is out of range" bench --count 0)
run(2 "--repeats: 0 is out of range" bench --repeats 0)
run(2 "--seed: '-1' is not a seed" bench --seed -1)
run(2 "--repeats: 0 is out of range" bench mesh --repeats 0)
run(2 "--size: 0 is out of range" bench mesh --size 0)
# the smallest size accepted still generates balls (48 tetrahedra: the grid step is capped at
# the radius), and each bench that generates them runs on them
run(0 "48 x 48 tetrahedra" bench mesh --size 6 --aligned-cells 0 --repeats 1)
run(0 "" bench resolve --size 6 --cases shallow --repeats 1)
run(2 "give both --a and --b" bench mesh --a ${FIXTURES}/meshes/tiny-a.msh)
run(2 "truncated.msh:.*truncated" bench mesh --a ${FIXTURES}/meshes/bad/truncated.msh --b ${FIXTURES}/meshes/tiny-b.msh)
# ... and end to end on small meshes (no timing asserted): files given, and generated balls.
run(0 "" bench mesh --a ${FIXTURES}/meshes/tiny-a.msh --b ${FIXTURES}/meshes/tiny-b.msh --repeats 1)
if(NOT out MATCHES "Stages of pdd::mesh::contacts" OR NOT out MATCHES "FCL DynamicAABBTreeCollisionManager")
  message(FATAL_ERROR "pdd bench mesh: table incomplete\n${out}")
endif()
# each aligned case beside B rotated and beside the whole scene turned (the same scene in
# another frame: it has intersecting pairs wherever the aligned one has)
if(NOT out MATCHES "\n +rotated +[0-9]+ +[1-9][0-9]* " OR NOT out MATCHES "\n +scene +[0-9]+ +[1-9][0-9]* "
   OR NOT out MATCHES "/ scene +[0-9.]+x +[0-9.]+x")
  message(FATAL_ERROR "pdd bench mesh: an aligned case without its rotated or turned scene's rows\n${out}")
endif()
# pdd bench end to end on a few pairs (no timing asserted): the slow-path rate and the cost of
# certification are in the report and in the JSON.
run(0 "" bench --count 20 --repeats 1 --exact-sample 2 --json ${WORK}/bench.json)
file(READ ${WORK}/bench.json bench_json)
if(NOT bench_json MATCHES "\"slow_path_pairs\": [0-9]" OR NOT bench_json MATCHES "\"rigid_pd2_uncertified_ns\": [0-9]")
  message(FATAL_ERROR "pdd bench --json: the certification block is incomplete\n${bench_json}")
endif()
run(0 "" bench mesh --size 600 --repeats 1 --json ${WORK}/bench-mesh.json)
file(READ ${WORK}/bench-mesh.json bench_mesh_json)
if(NOT bench_mesh_json MATCHES "\"intersecting_pairs\": [1-9]")
  message(FATAL_ERROR "pdd bench mesh --size 600: no intersecting pairs in the JSON\n${bench_mesh_json}")
endif()
if(NOT bench_mesh_json MATCHES "\"scene\": {[^}]*\"intersecting\": [1-9]" OR
   NOT bench_mesh_json MATCHES "\"depth_ratio_scene\": [0-9]")
  message(FATAL_ERROR "pdd bench mesh --json: an aligned case without its turned scene\n${bench_mesh_json}")
endif()

# ---- 4. pdd paper's arguments --------------------------------------------------------------
run(2 "--count: 0 is out of range" paper --count 0 --out ${WORK}/p)
run(2 "--exact-sample: 0 is out of range" paper --count 1 --exact-sample 0 --out ${WORK}/p)
run(2 "--repeats: 0 is out of range" paper --repeats 0 --out ${WORK}/p)
run(2 "--repeats: -3 is out of range" paper --repeats -3 --out ${WORK}/p)
run(2 "--min-volume: 'nan' is not a finite number" paper --min-volume nan --out ${WORK}/p)
run(2 "--min-volume \\(5\\) must be below --max-volume \\(1\\)" paper --min-volume 5 --max-volume 1 --out ${WORK}/p)
run(2 "pdd paper: cannot make the output folder '/dev/null/x'" paper --count 5 --out /dev/null/x)
run(2 "pdd paper: paper: no pair found" paper --count 1 --min-volume 400 --max-volume 500 --out ${WORK}/p)

# ---- 5. streaming: chunks of 4096 give the same records, in order ---------------------------
run(0 "" generate --family paper --count 4100 --seed 3 --output ${WORK}/many.json)
run(0 "4100 pairs, fast engine" solve --engine fast --input ${WORK}/many.json --output ${WORK}/many-file.jsonl)
run(0 "4100 pairs, fast engine" solve --engine fast --input /dev/stdin --output ${WORK}/many-pipe.jsonl STDIN ${WORK}/many.json)
file(STRINGS ${WORK}/many-file.jsonl recs)
list(LENGTH recs n)
list(GET recs 0 first)
list(GET recs 4099 last)
if(NOT n EQUAL 4100 OR NOT first MATCHES "^{\"name\":\"paper-3-0\"" OR NOT last MATCHES "^{\"name\":\"paper-3-4099\"")
  message(FATAL_ERROR "streamed solve: ${n} records, first ${first}")
endif()
file(SHA256 ${WORK}/many-file.jsonl h1)
file(SHA256 ${WORK}/many-pipe.jsonl h2)
if(NOT h1 STREQUAL h2)
  message(FATAL_ERROR "solve from a file and from a pipe differ")
endif()

# ---- --no-global: definitions §9 skipped; pdd2_global declined alone --------------------------
# A near-touching pair (a vertex ~1e-12 inside a face) is computed whole, pdd2_global included. adversarial-1-3 of fixtures/families (a vertex 1e-18
# inside a face) has its exact pdd2_relaxed below 1e-14 of its extent squared, where no double
# normal need attain pdd2_global: the fast engine declines that value alone (the allowed class):
# exit 1, the pair named on standard error, its definitions §9 keys null and every other value in
# the record; with --no-global no record carries definitions §9's keys and the exit status is 0.
file(WRITE ${WORK}/near.json "{\"pairs\":[{\"name\":\"near\",\"A\":[[9.037675410932524,1.693031294904751,5.424321574712652],[3.8210777667020013,4.148092997056115,6.978517449636188],[4.607158911182355,0.6403846042413175,9.325503552447756],[5.179261075285503,1.4998039580173883,4.764574921655386]],\"B\":[[5.095298979210175,2.44263248876802,7.508522662217512],[6.694381701516087,5.585622012955357,10.846255457025519],[7.076930292266666,1.7370670768927319,8.261623391742717],[4.324619576096192,4.561418815077989,10.29440907742961]]}]}")
run(0 "" solve --engine fast --quiet --input ${WORK}/near.json)
if(NOT out MATCHES "\"pdd2_global\":[0-9][^,]*,\"pdd2_global_normal\":\\[" OR NOT out MATCHES "\"pdd2_global_error\":null")
  message(FATAL_ERROR "solve (fast), near-touching: pdd2_global not computed\n${out}")
endif()
file(WRITE ${WORK}/declined.json "{\"pairs\":[{\"name\":\"near\",\"A\":[[1.484375,0.0390625,-2.0625],[-2.390625,-0.8359375,1.3125],[-2.640625,1.4765625,7.6875],[-4.765625,1.7890625,7.125]],\"B\":[[3.125,-0.875,-4.59375],[1.1875,-1.3125,-2.90625],[1.0625,-0.15625,0.28125],[-4.133520782600986e-18,1.5517643593698782e-18,6.179952383167375e-18]]}]}")
run(1 "pair 'near': pdd2_global declined: no normal in doubles" solve --engine fast --quiet --input ${WORK}/declined.json)
if(NOT out MATCHES "\"intersecting\":true,\"rigid_pd2\":1\\.52315146158976[0-9]*e-36" OR
   NOT out MATCHES "\"error\":null,\"pdd2_global\":null,\"pdd2_global_normal\":null,\"q1_A_global\":null,\"q1_B_global\":null,\"pdd2_global_error\":\"pdd2_global declined")
  message(FATAL_ERROR "solve (fast) with pdd2_global declined: wrong record\n${out}")
endif()
run(0 "took the exact path" solve --engine fast --no-global --input ${WORK}/declined.json)
if(out MATCHES "_global" OR NOT out MATCHES "\"intersecting\":true,\"rigid_pd2\":1\\.52315146158976[0-9]*e-36")
  message(FATAL_ERROR "solve --no-global (fast): wrong record\n${out}")
endif()
# --variants: only the values asked (a value with its label, q1_A and q1_B with pdd2), each the
# full record's (fixtures/golden/smoke.jsonl: nested-1 16/3, 4/5, 263/60; python/tests/test_variants.py
# compares every value bit for bit); the other
# values' keys left out; names as pdd mesh's; --no-global and --gradient keep their meaning.
run(0 "" solve --engine fast --quiet --variants rigid,pdd2 --input ${FIXTURES}/smoke.json)
if(NOT out MATCHES "^{\"name\":\"nested-1\",\"intersecting\":true,\"rigid_pd2\":5[.]333333333333333,\"pdd2\":0[.]8,\"rigid_dir\":\"FV:0\",\"pdd2_dir\":\"VF:0\",\"q1_A\":[^\n]*,\"q1_B\":[^\n]*,\"error\":null}\n"
   OR out MATCHES "static|relaxed|accel|eq11|_global")
  message(FATAL_ERROR "solve --variants rigid,pdd2: wrong records\n${out}")
endif()
run(0 "" ${SOLVE} --variants static --input ${FIXTURES}/smoke.json)
if(NOT out MATCHES "^{\"name\":\"nested-1\",\"intersecting\":true,\"pdd2_static\":\"263/60\",\"pdd2_static_dir\":\"FV:0\",\"error\":null}\n")
  message(FATAL_ERROR "solve --variants static (reference): wrong records\n${out}")
endif()
run(2 "--variants: unknown variant 'rigd'" solve --engine fast --variants rigid,rigd --input ${FIXTURES}/smoke.json)
run(2 "--no-global leaves nothing" solve --engine fast --variants global --no-global --input ${FIXTURES}/smoke.json)
run(2 "--gradient needs pdd2_global" solve --engine fast --variants pdd2 --gradient --input ${FIXTURES}/smoke.json)

# --format table and csv: one row per pair under a header, the same values as decimals (exact
# ones correctly rounded to 17 digits, marked '~' in the table: 16/3 and 4/5 below)
run(0 "" ${SOLVE} --format table --input ${FIXTURES}/smoke.json)
if(NOT out MATCHES "^name +intersecting +rigid_pd2 " OR NOT out MATCHES "\nnested-1 +true +~5\\.3333333333333333 +~0\\.083333333333333333 +~4\\.3833333333333333 +0\\.8 ")
  message(FATAL_ERROR "solve --format table: wrong rows\n${out}")
endif()
run(0 "" solve --engine fast --quiet --format csv --input ${FIXTURES}/smoke.json)
string(REGEX MATCHALL "\n" lines "${out}")
list(LENGTH lines n)
if(NOT n EQUAL 7 OR NOT out MATCHES "^name,intersecting,rigid_pd2,eq11_pd2,pdd2_static,pdd2,pdd2_relaxed,pdd2_accel1,pdd2_accel6,pdd2_global,rigid_dir,pdd2_static_dir,pdd2_dir,pdd2_relaxed_dir,error\n"
   OR NOT out MATCHES "\n\"poke-vertex-through-face\",true,0\\.25,0\\.25,0\\.015625,")
  message(FATAL_ERROR "solve --format csv: wrong rows\n${out}")
endif()
run(2 "--format: bogus not in" solve --format bogus --input ${FIXTURES}/smoke.json)
run(0 "" ${SOLVE} --no-global --input ${FIXTURES}/smoke.json)
if(out MATCHES "_global" OR NOT out MATCHES "\"pdd2\":\"4/5\"")
  message(FATAL_ERROR "solve --no-global (reference): wrong records\n${out}")
endif()

# ---- outputs that are inputs, and other hostile command lines ------------------------------
# An output that is an input would be emptied before it is read: refused, the input untouched.
file(COPY ${FIXTURES}/smoke.json DESTINATION ${WORK}/same)
file(SHA256 ${WORK}/same/smoke.json before)
run(2 "--output '.*smoke.json' is the input file" solve --engine fast --quiet --input ${WORK}/same/smoke.json --output ${WORK}/same/../same/smoke.json)
file(SHA256 ${WORK}/same/smoke.json after)
if(NOT before STREQUAL after)
  message(FATAL_ERROR "solve --output = --input changed the input")
endif()
file(COPY ${FIXTURES}/meshes/tiny-a.msh DESTINATION ${WORK}/same)
run(2 "--output '.*tiny-a.msh' is the same file as --a" mesh --a ${WORK}/same/tiny-a.msh --b ${FIXTURES}/meshes/tiny-b.msh --output ${WORK}/same/tiny-a.msh)
run(2 "--vtk '.*o.txt' is the same file as --output" mesh --a ${FIXTURES}/meshes/tiny-a.msh --b ${FIXTURES}/meshes/tiny-b.msh --output ${WORK}/same/o.txt --vtk ${WORK}/same/o.txt)
# A header that claims more items than the file has bytes (refused before allocating: 24 GB for
# a 300-byte file); a device and a directory as a mesh.
file(WRITE ${WORK}/same/lie.vtk "# vtk DataFile Version 3.0\nlie\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 1000000000 double\n0 0 0\n")
run(2 "lie.vtk:5: the number of points: 1000000000 is more than the [0-9]+ bytes left in the file" mesh --a ${WORK}/same/lie.vtk --b ${FIXTURES}/meshes/tiny-b.msh)
run(2 "'/dev/zero' is not a regular file" mesh --a /dev/zero --b ${FIXTURES}/meshes/tiny-b.msh)
run(2 "is a directory, not a mesh file" mesh --a ${WORK}/same --b ${FIXTURES}/meshes/tiny-b.msh)
# A folder without fixtures fails the golden check (not "0 of 0 match", exit 0).
file(MAKE_DIRECTORY ${WORK}/empty)
run(2 "no fixture files under" golden --check --fixtures ${WORK}/empty)
# A golden file holds computed records only: a flat pair makes --update write nothing (exit 1,
# the pair named) and --check fail naming it; a missing fixture folder is said in words.
file(MAKE_DIRECTORY ${WORK}/flatfix/golden)
file(WRITE ${WORK}/flatfix/flat.json "{\"pairs\":[{\"name\":\"ok\",\"A\":[[0,0,0],[4,0,0],[0,4,0],[0,0,4]],\"B\":[[1,1,1],[2,1,1],[1,2,1],[1,1,2]]},{\"name\":\"flat\",\"A\":[[0,0,0],[1,0,0],[0,1,0],[1,1,0]],\"B\":[[1,1,1],[2,1,1],[1,2,1],[1,1,2]]}]}")
run(1 "nothing written: .*flat.json: pair 'flat': tetrahedron A is flat" golden --update --quiet --fixtures ${WORK}/flatfix)
if(EXISTS ${WORK}/flatfix/golden/flat.jsonl)
  message(FATAL_ERROR "golden --update wrote a golden file holding a rejected pair")
endif()
file(WRITE ${WORK}/flatfix/golden/flat.jsonl "")
run(1 "" golden --check --quiet --fixtures ${WORK}/flatfix)
if(NOT out MATCHES "MISMATCH flat.json: pair 'flat': tetrahedron A is flat[^\n]*rejected")
  message(FATAL_ERROR "golden --check with a flat pair:\n${out}")
endif()
run(2 "no fixture folder '${WORK}/nowhere'" golden --check --fixtures ${WORK}/nowhere)
run(2 "not a finite number" bench mesh --size 200 --distance nan)
# bench --json to a path that cannot be written: said before the run, not after it.
run(2 "cannot write '/nonexistent-dir/b.json'" bench --count 10 --repeats 1 --json /nonexistent-dir/b.json)
run(2 "cannot write '/nonexistent-dir/m.json'" bench mesh --size 200 --repeats 1 --json /nonexistent-dir/m.json)
# Mesh headers that contradict their contents (refused): a point type that is no VTK
# type, a legacy CELLS size that is not the list's length, an MSH 4.1 node tag outside the
# $Nodes header's range.
file(WRITE ${WORK}/same/type.vtk "# vtk DataFile Version 2.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 quaternion\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n")
run(2 "type.vtk:5: 'quaternion' is not a VTK data type" mesh --a ${WORK}/same/type.vtk --b ${FIXTURES}/meshes/tiny-b.msh)
file(WRITE ${WORK}/same/size.vtk "# vtk DataFile Version 2.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\nCELLS 1 3\n4 0 1 2 3\nCELL_TYPES 1\n10\n")
run(2 "size.vtk:10: the cell list has 5 numbers, not the 3 its header says" mesh --a ${WORK}/same/size.vtk --b ${FIXTURES}/meshes/tiny-b.msh)
file(WRITE ${WORK}/same/tag.msh "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 3\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n")
run(2 "tag.msh:[0-9]+: node tag 4 is outside the \\$Nodes header's range \\[1, 3\\]" mesh --a ${WORK}/same/tag.msh --b ${FIXTURES}/meshes/tiny-b.msh)
# A pair name with a newline and a terminal escape: shown as \xNN in messages, never raw.
file(WRITE ${WORK}/same/esc.json "{\"pairs\":[{\"name\":\"bad\\nname\\u001b[31m\",\"A\":[[0,0,0],[1,0,0],[0,1,0],[1,1,0]],\"B\":[[0,0,0],[1,0,0],[0,1,0],[0,0,1]]}]}")
run(1 "pair 'bad\\\\x0aname\\\\x1b\\[31m' rejected: tetrahedron A is flat" solve --engine fast --quiet --input ${WORK}/same/esc.json)
