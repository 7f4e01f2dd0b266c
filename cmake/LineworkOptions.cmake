# Warnings for our own targets, CUDA enablement and small helpers shared by the modules.

function(linework_warnings target)
    if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
        target_compile_options(${target} PRIVATE
            $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wno-missing-field-initializers>)
    endif()
endfunction()

# CUDA: AUTO enables it when nvcc works, ON requires it, OFF skips it. Architectures are
# explicit because `native` fails on machines without a GPU (CI, developer machines).
set(LINEWORK_CUDA_ENABLED OFF)
if(NOT LINEWORK_CUDA STREQUAL "OFF")
    include(CheckLanguage)
    if(NOT CMAKE_CUDA_ARCHITECTURES)
        set(CMAKE_CUDA_ARCHITECTURES "75;80;86;89;90" CACHE STRING "CUDA architectures")
    endif()
    check_language(CUDA)
    if(CMAKE_CUDA_COMPILER)
        enable_language(CUDA)
        set(CMAKE_CUDA_STANDARD 17)
        set(CMAKE_CUDA_STANDARD_REQUIRED ON)
        set(LINEWORK_CUDA_ENABLED ON)
    elseif(LINEWORK_CUDA STREQUAL "ON")
        message(FATAL_ERROR "LINEWORK_CUDA=ON but no working nvcc was found")
    endif()
endif()

# Sanitizers (issue 10): LINEWORK_SANITIZE=address,undefined instruments every target (the CMake
# preset `asan`, build/asan). UBSan stops at the first finding so a test fails on it; the tests
# get the runtime options below, third-party leak suppressions from tests/sanitizers/lsan.supp.
set(LINEWORK_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined")
# LINEWORK_FUZZ=ON (clang only) adds libFuzzer's coverage instrumentation to every target and
# builds the fuzz targets of tests/fuzz (`cmake --build DIR --target lw_fuzzers`).
option(LINEWORK_FUZZ "Build the libFuzzer targets (needs clang)" OFF)
if(LINEWORK_FUZZ)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        message(FATAL_ERROR "LINEWORK_FUZZ=ON needs clang (libFuzzer), not ${CMAKE_CXX_COMPILER_ID}")
    endif()
    add_compile_options(-fsanitize=fuzzer-no-link)
endif()
set(LINEWORK_SANITIZER_ENV "")
if(LINEWORK_SANITIZE)
    add_compile_options(-fsanitize=${LINEWORK_SANITIZE} -fno-omit-frame-pointer
                        -fno-sanitize-recover=undefined)
    add_link_options(-fsanitize=${LINEWORK_SANITIZE})
    set(LINEWORK_SANITIZER_ENV
        "ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
        "LSAN_OPTIONS=suppressions=${CMAKE_SOURCE_DIR}/tests/sanitizers/lsan.supp:print_suppressions=0"
        "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
    # The GUI tests: Debian 12's libxkbcommon-x11 (1.5) reads past the end of an xcb reply
    # with strndup while Qt's xcb plugin loads the keymap, at start-up of every QApplication.
    # It is not ours to fix; ASan's strndup check is off for those processes only (Linework's
    # code never calls strndup).
    set(LINEWORK_SANITIZER_ENV_GUI ${LINEWORK_SANITIZER_ENV})
    list(TRANSFORM LINEWORK_SANITIZER_ENV_GUI APPEND ":intercept_strndup=0" REGEX "^ASAN_OPTIONS=")
endif()

# linework_gl_tests_without_leak_check(test ...): tests whose process, or a linework-cli it starts,
# opens OpenGL (Mesa). In the sanitizer suite LeakSanitizer is off for them; memory-error and
# undefined-behaviour checks stay on. Two reasons, both Mesa's: its DRI driver allocates small
# blocks once per process and is unloaded at exit, so leaks are reported with stacks naming
# "<unknown module>" that no suppression can match; and llvmpipe's worker threads are still
# alive at exit (the EGL display is a per-process singleton and is never terminated), where
# LeakSanitizer's stop-the-world tracer now and then crashes ("Tracer caught signal 11",
# google/sanitizers#1353) and fails a test whose work passed. Every test without GL keeps leak
# checking. `gui` selects the GUI tests' runtime options (see LINEWORK_SANITIZER_ENV_GUI).
function(linework_gl_tests_without_leak_check)
    if(NOT LINEWORK_SANITIZE)
        return()
    endif()
    cmake_parse_arguments(ARG "GUI" "" "TESTS" ${ARGN})
    if(ARG_GUI)
        set(env ${LINEWORK_SANITIZER_ENV_GUI})
    else()
        set(env ${LINEWORK_SANITIZER_ENV})
    endif()
    list(TRANSFORM env APPEND ":detect_leaks=0" REGEX "^ASAN_OPTIONS=")
    foreach(test IN LISTS ARG_TESTS)
        if(TEST ${test})
            set_property(TEST ${test} APPEND PROPERTY ENVIRONMENT ${env})
        endif()
    endforeach()
endfunction()

# A test that needs a resource it cannot find exits with this code; CTest reports it as SKIP.
set(LINEWORK_SKIP_CODE 77)

# linework_add_gtest(name SOURCES ... LIBS ... LABELS unit|data|gl|gpu [REQUIRES_DATA|REQUIRES_GL|REQUIRES_CUDA])
# REQUIRES_DATA / REQUIRES_GL: the test's main exits with the SKIP code when ../shared/data is
# missing / no headless OpenGL context can be made / no CUDA device is present (the GL main keeps the context current for the
# tests: lw::test::glContext()), so CTest reports SKIP instead of a PASS that tested nothing.
function(linework_add_gtest name)
    cmake_parse_arguments(ARG "REQUIRES_DATA;REQUIRES_GL;REQUIRES_CUDA" "" "SOURCES;LIBS;LABELS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    if(ARG_REQUIRES_CUDA)
        target_link_libraries(${name} PRIVATE ${ARG_LIBS} lw_gtest_main_cuda GTest::gtest)
    elseif(ARG_REQUIRES_DATA)
        target_link_libraries(${name} PRIVATE ${ARG_LIBS} lw_gtest_main_data GTest::gtest)
    elseif(ARG_REQUIRES_GL)
        target_link_libraries(${name} PRIVATE ${ARG_LIBS} lw_gtest_main_gl GTest::gtest)
    else()
        target_link_libraries(${name} PRIVATE ${ARG_LIBS} lw_gtest_main GTest::gtest)
    endif()
    linework_warnings(${name})
    add_test(NAME ${name} COMMAND ${name})
    set_tests_properties(${name} PROPERTIES
        LABELS "${ARG_LABELS}"
        SKIP_RETURN_CODE ${LINEWORK_SKIP_CODE}
        ENVIRONMENT "LINEWORK_SHARED_DATA=${LINEWORK_SHARED_DATA};LINEWORK_SOURCE_DIR=${CMAKE_SOURCE_DIR};${LINEWORK_SANITIZER_ENV}")
endfunction()
