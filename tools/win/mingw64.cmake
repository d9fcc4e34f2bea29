# CMake toolchain for Windows x64 with Debian's mingw-w64 (tools/win/build.sh).
# The posix thread model of gcc: std::thread and std::mutex, which TBB and
# OpenVDB need, exist only there in GCC 12 (its win32 model lacks them), and
# its runtime is winpthreads (libwinpthread-1.dll).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR AMD64)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc-posix)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++-posix)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_AR x86_64-w64-mingw32-gcc-ar-posix CACHE FILEPATH "")
set(CMAKE_RANLIB x86_64-w64-mingw32-gcc-ranlib-posix CACHE FILEPATH "")
# Only the target's own prefix (BANYAN_WIN_PREFIX) and mingw's sysroot are searched.
set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32 $ENV{BANYAN_WIN_PREFIX})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_CROSSCOMPILING_EMULATOR wine64)
