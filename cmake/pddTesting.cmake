# pddTesting.cmake — CTest labels. Every test has exactly one label, naming the part of pdd it
# exercises, so that a run can select by label (`ctest -L fast`):
#   fast       the fast engine (tests/fast)          reference  the exact engine (tests/reference)
#   compare    the harness and research (tests/compare, the fast engine's fuzz replay)
#   mesh       pdd::mesh (tests/mesh)               python     the Python module (python/tests)
#   cli        the `pdd` program and the installed package (tests/cli, examples/, the fixture
#              reader's fuzz replay)
# pdd_test_label also records the targets the test runs; pdd_label_targets (at the end of the
# top-level CMakeLists.txt) makes one target per label, pdd_tests_<label>, that builds exactly
# those: scripts/sanitize.sh builds the targets of the labels it runs.
set(PDD_TEST_LABELS fast reference compare mesh python cli)

# pdd_test_label(<test> <label> <target>...): <test>'s label and the targets it runs.
function(pdd_test_label test label)
  if(NOT label IN_LIST PDD_TEST_LABELS)
    message(FATAL_ERROR "test ${test}: label '${label}' is not one of ${PDD_TEST_LABELS}")
  endif()
  set_tests_properties(${test} PROPERTIES LABELS ${label})
  set_property(GLOBAL APPEND PROPERTY PDD_LABELLED_TESTS ${test})
  set_property(GLOBAL APPEND PROPERTY PDD_TEST_TARGETS_${label} ${ARGN})
endfunction()

# Every test of `dir` and below must have a label (a new test without one fails the configure).
function(pdd_check_labels dir)
  get_property(tests DIRECTORY ${dir} PROPERTY TESTS)
  get_property(labelled GLOBAL PROPERTY PDD_LABELLED_TESTS)
  foreach(test IN LISTS tests)
    if(NOT test IN_LIST labelled)
      message(FATAL_ERROR "test ${test} has no label: give it one with pdd_test_label "
                          "(cmake/pddTesting.cmake)")
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    pdd_check_labels(${sub})
  endforeach()
endfunction()

# pdd_tests_<label>: builds what the tests of <label> run (targets this build has).
function(pdd_label_targets)
  pdd_check_labels(${PROJECT_SOURCE_DIR})
  foreach(label IN LISTS PDD_TEST_LABELS)
    get_property(targets GLOBAL PROPERTY PDD_TEST_TARGETS_${label})
    set(built)
    foreach(t IN LISTS targets)
      if(TARGET ${t})
        list(APPEND built ${t})
      endif()
    endforeach()
    add_custom_target(pdd_tests_${label})
    if(built)
      list(REMOVE_DUPLICATES built)
      add_dependencies(pdd_tests_${label} ${built})
    endif()
  endforeach()
endfunction()
