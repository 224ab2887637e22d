# Build targets for a subset of the tests, so that a CI stage that runs some labels builds only
# what those tests run (scripts/test: the ThreadSanitizer stage runs the threading and
# integration tests and would otherwise compile every unit test too, a third of the tree):
#   stepmod_product   every target outside tests/ and bench/ (the programs, their libraries,
#                     generated files): what the script and daemon tests start
#   tests_<label>     stepmod_product and the test programs that carry <label>
# stepmod_gtest (tests/CMakeLists.txt) records each test program under its label; a test program
# made otherwise registers itself with stepmod_register_test_program(<target> <label>).

function(stepmod_register_test_program target label)
  set_property(GLOBAL APPEND PROPERTY STEPMOD_TEST_PROGRAMS_${label} ${target})
  set_property(GLOBAL APPEND PROPERTY STEPMOD_TEST_LABELS ${label})
endfunction()

# The targets defined in `dir` and below it, leaving out tests/ and bench/.
function(stepmod_product_targets dir out)
  get_property(defined DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  set(targets "")
  foreach(t IN LISTS defined)
    # What `all` builds: no interface libraries (nothing to build), nothing excluded from all.
    get_target_property(type ${t} TYPE)
    get_target_property(excluded ${t} EXCLUDE_FROM_ALL)
    if(NOT type STREQUAL "INTERFACE_LIBRARY" AND NOT excluded)
      list(APPEND targets ${t})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    file(RELATIVE_PATH rel ${CMAKE_SOURCE_DIR} ${sub})
    if(rel MATCHES "^(tests|bench)(/|$)")
      continue()
    endif()
    stepmod_product_targets(${sub} more)
    list(APPEND targets ${more})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

# Called once, at the end of the top-level CMakeLists.txt, when every target exists.
function(stepmod_add_test_targets)
  stepmod_product_targets(${CMAKE_SOURCE_DIR} product)
  add_custom_target(stepmod_product)
  add_dependencies(stepmod_product ${product})
  get_property(labels GLOBAL PROPERTY STEPMOD_TEST_LABELS)
  list(REMOVE_DUPLICATES labels)
  foreach(label IN LISTS labels)
    get_property(programs GLOBAL PROPERTY STEPMOD_TEST_PROGRAMS_${label})
    add_custom_target(tests_${label})
    add_dependencies(tests_${label} stepmod_product ${programs})
  endforeach()
endfunction()
