# radwalk_options: an INTERFACE target every radwalk target links, carrying warnings and sanitizers.
add_library(radwalk_options INTERFACE)
target_compile_options(radwalk_options INTERFACE -Wall -Wextra -Wpedantic)
# RADWALK_SANITIZE: OFF, ON (= address,undefined) or a -fsanitize= list such as address,undefined (g++ or clang;
# scripts/sanitize.sh builds build-asan/ with it and runs the suite there).
if(RADWALK_SANITIZE)
  if(RADWALK_SANITIZE MATCHES "^(ON|on|On|TRUE|true|YES|yes|1)$")
    set(radwalk_sanitizers address,undefined)
  else()
    set(radwalk_sanitizers ${RADWALK_SANITIZE})
  endif()
  target_compile_options(radwalk_options INTERFACE -fsanitize=${radwalk_sanitizers} -fno-omit-frame-pointer
                                                   -fno-sanitize-recover=undefined)
  target_link_options(radwalk_options INTERFACE -fsanitize=${radwalk_sanitizers})
endif()
# The fuzz tree: libFuzzer's coverage instrumentation in every library (the harness executables of tests/fuzz add
# -fsanitize=fuzzer, libFuzzer's main), ASan + UBSan, -O1 with debug information and assertions (Eigen's too).
if(RADWALK_FUZZ)
  target_compile_options(radwalk_options INTERFACE -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                                                   -fno-sanitize-recover=undefined -O1 -g)
  target_link_options(radwalk_options INTERFACE -fsanitize=address,undefined)
endif()

# radwalk_add_layer(NAME SOURCES... DEPS ...): one static library per layer, src/ as include root.
function(radwalk_add_layer name)
  cmake_parse_arguments(L "" "" "SOURCES;DEPS" ${ARGN})
  add_library(radwalk_${name} STATIC ${L_SOURCES})
  target_include_directories(radwalk_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(radwalk_${name} PUBLIC radwalk_options ${L_DEPS})
endfunction()

# radwalk_add_test(NAME SOURCES... DEPS ...): one Catch2 executable linking the test support (tests/support), each
# TEST_CASE discovered as a CTest test; hidden cases (tag "[.]", run only by name) are left out.
function(radwalk_add_test name)
  cmake_parse_arguments(T "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${T_SOURCES} $<TARGET_OBJECTS:radwalk_test_scratch>)
  target_link_libraries(${name} PRIVATE radwalk_options Catch2::Catch2WithMain radwalk_test_support ${T_DEPS})
  target_compile_definitions(${name} PRIVATE RADWALK_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  set(env "")
  if(RADWALK_SANITIZE)
    set(env "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/tests/lsan.supp:print_suppressions=0")
  endif()
  catch_discover_tests(${name} TEST_SPEC "~[slow]~[.]" EXTRA_ARGS --warn NoTests PROPERTIES TIMEOUT 600 ENVIRONMENT "${env}")
  catch_discover_tests(${name} TEST_SPEC "[slow]" TEST_PREFIX "slow: " EXTRA_ARGS --warn NoTests PROPERTIES TIMEOUT 3600 LABELS slow
                       ENVIRONMENT "${env}")
endfunction()
