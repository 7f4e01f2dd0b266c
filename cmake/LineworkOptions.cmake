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
        ENVIRONMENT "LINEWORK_SHARED_DATA=${LINEWORK_SHARED_DATA};LINEWORK_SOURCE_DIR=${CMAKE_SOURCE_DIR}")
endfunction()
