# `pdd paper` on 120 pairs, every one also solved exactly: exit 0, every artefact written, and
# the numbers pdd computed checked against each other: the fast engine's Table I row and
# direction statistics must print exactly what the exact engine's do on the same pairs (the
# fast engine is within 1e-9 of exact, far below the two printed decimals; its labels agree
# exactly or by an exact tie). The paper's own numbers, printed from constants, are not checked.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${PDD} paper --seed 7 --count 120 --exact-sample 120 --repeats 1 --out ${OUT}
                        --fixtures ${FIXTURES}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pdd paper: exit ${rc}\n${err}")
endif()
foreach(f report.md fig3_histograms.png fig2_pair.png pair_before_after.vtk)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "pdd paper did not write ${f}\n${err}")
  endif()
endforeach()
file(READ ${OUT}/report.md report)
foreach(needle "## Table I" "120 pairs drawn at random (seed 7) and solved exactly: 0 over the tolerance"
               "![PD_d/PD histograms]")
  string(FIND "${report}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "report.md lacks '${needle}'")
  endif()
endforeach()

# The rest of the line after `prefix` (the first line holding it).
function(row_after prefix var)
  string(FIND "${report}" "${prefix}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "report.md lacks the row '${prefix}'\n${report}")
  endif()
  string(LENGTH "${prefix}" n)
  math(EXPR at "${at} + ${n}")
  string(SUBSTRING "${report}" ${at} -1 rest)
  string(FIND "${rest}" "\n" eol)
  string(SUBSTRING "${rest}" 0 ${eol} row)
  set(${var} "${row}" PARENT_SCOPE)
endfunction()

# Table I: PD_d/PD per variant, mean (standard deviation), fast over all 120 pairs and exact
# over the same 120.
row_after("| PD_d/PD, pdd fast, 120 pairs |" fast_row)
row_after("| PD_d/PD, pdd exact, 120-pair sample |" exact_row)
if(NOT fast_row MATCHES "^( [0-9]+\\.[0-9][0-9]% \\([0-9]+\\.[0-9][0-9]%\\) \\|)+$")
  message(FATAL_ERROR "unexpected Table I row: '${fast_row}'")
endif()
if(NOT fast_row STREQUAL exact_row)
  message(FATAL_ERROR "Table I: fast '${fast_row}' but exact '${exact_row}' on the same pairs")
endif()

# Directions: "| what | paper | fast | exact |", fast and exact on the same pairs.
foreach(what "| rigid direction = optimal case-2 direction |"
             "| case-2 optimum among the first six (depth order) |")
  row_after("${what}" row)
  if(NOT row MATCHES "^ [^|]+ \\| ([0-9.]+%) \\| ([0-9.]+%) \\|$")
    message(FATAL_ERROR "unexpected directions row: '${what}${row}'")
  endif()
  if(NOT CMAKE_MATCH_1 STREQUAL CMAKE_MATCH_2)
    message(FATAL_ERROR "${what}: fast ${CMAKE_MATCH_1} but exact ${CMAKE_MATCH_2} on the same pairs")
  endif()
endforeach()

# definitions §9 on the fixture families: a row per shipped family file, and on every family where
# both engines count the same pairs the fast pdd2_relaxed / pdd2_global column prints what the exact
# one (read from the golden files) does (within 2e-9 of each other, far below 5 digits).
file(GLOB family_files RELATIVE ${FIXTURES}/families ${FIXTURES}/families/*.json)
list(LENGTH family_files n_families)
if(n_families LESS 10)
  message(FATAL_ERROR "expected the shipped families in ${FIXTURES}/families, found ${n_families}")
endif()
string(FIND "${report}" "### The same on the fixture families" at)
if(at EQUAL -1)
  message(FATAL_ERROR "report.md lacks the fixture families' table")
endif()
string(SUBSTRING "${report}" ${at} -1 report)  # row_after searches the table only from here on
foreach(f ${family_files})
  string(REGEX REPLACE "\\.json$" "" family "${f}")
  row_after("| ${family} | " row)
  if(NOT row MATCHES "^[0-9]+ \\| ([0-9]+) / ([0-9]+) \\| ([^|]+) \\| ([^|]+) \\|")
    message(FATAL_ERROR "unexpected family row: '| ${family} | ${row}'")
  endif()
  if(CMAKE_MATCH_1 STREQUAL CMAKE_MATCH_2 AND NOT CMAKE_MATCH_3 STREQUAL CMAKE_MATCH_4)
    message(FATAL_ERROR "family ${family}: fast '${CMAKE_MATCH_3}' but exact '${CMAKE_MATCH_4}'")
  endif()
endforeach()
