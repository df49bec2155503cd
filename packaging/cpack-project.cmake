# Read by cpack when it makes the package (CPACK_PROJECT_CONFIG_FILE), not at configure time: the
# package version follows the checked-out commit, 0.<number of commits>+g<short hash>, so each new
# commit gives a newer package without reconfiguring the build. Outside a git checkout: 0.
execute_process(COMMAND git -C "${CPACK_YADE_CAPILLARY_SOURCE_DIR}" rev-list --count HEAD
  OUTPUT_VARIABLE _count RESULT_VARIABLE _count_status OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git -C "${CPACK_YADE_CAPILLARY_SOURCE_DIR}" rev-parse --short HEAD
  OUTPUT_VARIABLE _hash RESULT_VARIABLE _hash_status OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(_count_status EQUAL 0 AND _hash_status EQUAL 0)
  set(CPACK_PACKAGE_VERSION "0.${_count}+g${_hash}")
else()
  set(CPACK_PACKAGE_VERSION "0")
endif()
