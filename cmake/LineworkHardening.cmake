# Hardening as Debian builds its packages: fortified libc calls and a strong stack protector
# (dpkg-buildflags' defaults on Debian 12), so an overflow in code that parses hostile files
# stops the program instead of running on; and immediate binding, which with the linker's default
# read-only relocations makes the whole global offset table read-only (full RELRO; Debian's
# "hardening=+all"). Position-independent executables are the Debian compiler's default already.
# lintian checks the packaged programs for these (tests/installer/package_test.sh).
option(LINEWORK_HARDENING "Build with Debian's hardening flags (GCC and Clang)" ON)
if(LINEWORK_HARDENING AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    add_compile_options($<$<COMPILE_LANGUAGE:C,CXX>:-fstack-protector-strong>)
    # _FORTIFY_SOURCE needs the optimiser; in a Debug build it would only warn.
    add_compile_options($<$<AND:$<COMPILE_LANGUAGE:C,CXX>,$<NOT:$<CONFIG:Debug>>>:-D_FORTIFY_SOURCE=2>)
    # LINKER: reaches the linker through nvcc too, where CUDA links a target.
    add_link_options(LINKER:-z,relro LINKER:-z,now)
endif()
