# Included by ctest after the unit tests found in unit_tests and project_tests (tests/CMakeLists.txt): each is in
# the `unit`, `quick` and `pr` tiers, and holds a core while it runs (tests/CMakeLists.txt, "What a test holds").
foreach(unit_test IN LISTS unit_tests_TESTS project_tests_TESTS)
  set_tests_properties("${unit_test}" PROPERTIES LABELS "unit;quick;pr" RESOURCE_GROUPS "cores:1")
endforeach()
