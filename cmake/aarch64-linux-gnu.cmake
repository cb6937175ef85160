# Cross-compiling for aarch64 (arm64) with Debian's g++-aarch64-linux-gnu against a sysroot of
# Debian's arm64 packages (scripts/aarch64_sysroot.sh); tests run under qemu-user.
#   cmake -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DENHANCED_ORB_SYSROOT=DIR ...
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(ENHANCED_ORB_SYSROOT "" CACHE PATH "Root of the unpacked arm64 packages")
# The cross compiler brings its own libc and libstdc++; the sysroot adds OpenCV, GoogleTest and
# their dependencies, searched there only.
set(CMAKE_FIND_ROOT_PATH ${ENHANCED_ORB_SYSROOT})
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# The libraries' own dependencies (gdal, tbb, ...) resolve in the sysroot at link and at run time.
set(CMAKE_EXE_LINKER_FLAGS_INIT
  "-Wl,-rpath-link,${ENHANCED_ORB_SYSROOT}/usr/lib/aarch64-linux-gnu -Wl,-rpath-link,${ENHANCED_ORB_SYSROOT}/lib/aarch64-linux-gnu -Wl,-rpath-link,${ENHANCED_ORB_SYSROOT}/usr/lib")
set(CMAKE_SHARED_LINKER_FLAGS_INIT "${CMAKE_EXE_LINKER_FLAGS_INIT}")
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L ${ENHANCED_ORB_SYSROOT})
