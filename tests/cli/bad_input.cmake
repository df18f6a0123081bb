# `pdd solve` on bad input: a mixed batch exits 1 with one record per pair (7 errors, 2
# results); unreadable, empty and malformed files exit 2 with a message naming the problem.
function(expect_exit code out_var)
  execute_process(COMMAND ${PDD} solve --engine reference --quiet ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL ${code})
    message(FATAL_ERROR "pdd solve ${ARGN}: exit ${rc}, expected ${code}\n${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${out_var}_err "${err}" PARENT_SCOPE)
endfunction()

expect_exit(1 mixed --input ${FIXTURES}/bad/mixed.json --formulation reduced)
string(REGEX MATCHALL "\"error\":\"[^\"]+\"" errors "${mixed}")
string(REGEX MATCHALL "\"error\":null" oks "${mixed}")
list(LENGTH errors n_err)
list(LENGTH oks n_ok)
if(NOT n_err EQUAL 7 OR NOT n_ok EQUAL 2)
  message(FATAL_ERROR "mixed batch: ${n_err} error records and ${n_ok} results, expected 7 and 2")
endif()
if(NOT mixed_err MATCHES "pair 'flat-A' rejected: tetrahedron A is flat")
  message(FATAL_ERROR "stderr does not name the flat pair:\n${mixed_err}")
endif()

foreach(f empty malformed no-pairs does-not-exist)
  expect_exit(2 out --input ${FIXTURES}/bad/${f}.json)
  if(NOT out STREQUAL "")
    message(FATAL_ERROR "${f}: unexpected output ${out}")
  endif()
endforeach()
expect_exit(2 out --input ${FIXTURES}/smoke.json --engine nonsense)

# --gradient with a format that has no gradient column is refused (exit 2, nothing written)
# rather than the gradient being dropped.
foreach(f table csv)
  expect_exit(2 out --input ${FIXTURES}/smoke.json --gradient --format ${f})
  if(NOT out STREQUAL "" OR NOT out_err MATCHES "--gradient needs --format jsonl")
    message(FATAL_ERROR "--gradient --format ${f}: output '${out}', message '${out_err}'")
  endif()
endforeach()

# --help names the default engine in words (not only CLI11's "=reference").
execute_process(COMMAND ${PDD} solve --help RESULT_VARIABLE rc OUTPUT_VARIABLE help)
if(NOT rc EQUAL 0 OR NOT help MATCHES "'reference' \\(exact[^)]*; the default here\\)")
  message(FATAL_ERROR "pdd solve --help does not name the default engine:\n${help}")
endif()
