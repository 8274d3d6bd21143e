# Included by ctest after the unit tests found in unit_tests and project_tests (tests/CMakeLists.txt): each is in
# the `unit`, `quick` and `pr` tiers.
foreach(unit_test IN LISTS unit_tests_TESTS project_tests_TESTS)
  set_tests_properties("${unit_test}" PROPERTIES LABELS "unit;quick;pr")
endforeach()
