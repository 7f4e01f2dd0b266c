# Locate nvcc before project(): PATH first, then the usual install prefix. Sets
# CMAKE_CUDA_COMPILER only when the user did not, and only when LINEWORK_CUDA is not OFF.
if(NOT DEFINED LINEWORK_CUDA OR NOT LINEWORK_CUDA STREQUAL "OFF")
    if(NOT CMAKE_CUDA_COMPILER AND NOT DEFINED ENV{CUDACXX})
        find_program(LINEWORK_NVCC nvcc PATHS /usr/local/cuda/bin NO_CACHE)
        if(LINEWORK_NVCC)
            set(CMAKE_CUDA_COMPILER "${LINEWORK_NVCC}" CACHE FILEPATH "CUDA compiler")
        endif()
    endif()
endif()
