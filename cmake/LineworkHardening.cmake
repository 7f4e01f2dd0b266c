# Hardening as Debian builds its own packages (dpkg-buildflags' defaults on Debian 12): fortified
# libc calls and a strong stack protector, so an overflow in code that parses hostile files
# stops the program instead of running on. Position-independent executables and read-only
# relocations are the Debian compiler's and linker's defaults already. lintian checks the
# packaged programs for these (tests/installer/package_test.sh). Immediate binding (-z now) is
# not a Debian default either: it would resolve every Qt symbol at start for no gain here.
option(LINEWORK_HARDENING "Build with Debian's default hardening flags (GCC and Clang)" ON)
if(LINEWORK_HARDENING AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    add_compile_options($<$<COMPILE_LANGUAGE:C,CXX>:-fstack-protector-strong>)
    # _FORTIFY_SOURCE needs the optimiser; in a Debug build it would only warn.
    add_compile_options($<$<AND:$<COMPILE_LANGUAGE:C,CXX>,$<NOT:$<CONFIG:Debug>>>:-D_FORTIFY_SOURCE=2>)
endif()
