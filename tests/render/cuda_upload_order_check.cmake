# A source rule for the CUDA back-end: no host-to-device upload with the synchronous cudaMemcpy
# family. From pageable memory such a copy may return once the data is staged, before its DMA
# lands, and the back-end's kernels run on non-blocking streams that are not ordered after it:
# a fresh volume's first kernels could read it half-written (a frame with no surface, now and
# then, only under load). An upload goes on the stream that reads it (cudaMemcpyAsync); the
# constant tables, uploaded once with cudaMemcpyToSymbol, are synchronised right after.
#   cmake -DCUDA_SOURCES=<kernels/cuda/src> -P cuda_upload_order_check.cmake
if(NOT IS_DIRECTORY "${CUDA_SOURCES}")
    message(FATAL_ERROR "CUDA_SOURCES: not a folder: '${CUDA_SOURCES}'")
endif()
file(GLOB_RECURSE sources "${CUDA_SOURCES}/*.cu" "${CUDA_SOURCES}/*.cuh" "${CUDA_SOURCES}/*.h"
     "${CUDA_SOURCES}/*.cpp")
list(LENGTH sources sourceCount)
if(sourceCount EQUAL 0)
    message(FATAL_ERROR "no CUDA sources under ${CUDA_SOURCES}")
endif()
set(offences "")
set(calls 0)
foreach(source ${sources})
    file(READ "${source}" text)
    # A call, not a status label ("cudaMemcpy(volume)"): not after a quote or a name character;
    # everything up to its semicolon.
    string(REGEX MATCHALL "[^\"A-Za-z0-9_]cudaMemcpy(2D|3D)?\\([^;]*;" found "${text}")
    foreach(call ${found})
        math(EXPR calls "${calls} + 1")
        if(call MATCHES "cudaMemcpyHostToDevice|cudaMemcpyDefault")
            string(REGEX REPLACE "[ \n]+" " " oneLine "${call}")
            string(APPEND offences "\n  ${source}:${oneLine}")
        endif()
    endforeach()
    if(text MATCHES "cudaMemcpyToSymbol\\(" AND NOT text MATCHES "cudaDeviceSynchronize\\(")
        string(APPEND offences "\n  ${source}: cudaMemcpyToSymbol without cudaDeviceSynchronize")
    endif()
endforeach()
if(offences)
    message(FATAL_ERROR "synchronous host-to-device uploads (use cudaMemcpyAsync on the stream "
                        "that reads the data):${offences}")
endif()
message(STATUS "${sourceCount} CUDA sources, ${calls} synchronous copies, none host to device")
