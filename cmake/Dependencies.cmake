# Every third-party dependency of the product, found once here, from Debian bookworm packages.
# The Debian packaging workarounds (numbered P1, P2, P4, P7, each explained where it is applied) live here and
# nowhere else.
# scripts/install-deps.sh installs the packages these calls need.

find_package(Threads REQUIRED)

# --- ANTLR: tool 4.7.2 generates C++ at build time, runtime 4.9 ------------------------------------
find_package(antlr4-runtime CONFIG REQUIRED)          # antlr4_shared / antlr4_static, ANTLR4_INCLUDE_DIR
find_program(ANTLR4_TOOL antlr4 REQUIRED)             # Debian's wrapper sets the Java classpath (P4)

# --- maths, formatting, command lines, JSON ---------------------------------------------------------
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)

# --- robot world: MuJoCo, OMPL, FCL -------------------------------------------------------------------
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)   # mujoco's config needs OpenGL; rendering needs EGL
find_package(mujoco CONFIG REQUIRED)
# P1: Debian's mujoco target lists /usr/include/libqhull_r/, which exists only with libqhull-dev.
get_target_property(_cbtl_mj_inc mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
set(_cbtl_mj_inc_ok)
foreach(_d IN LISTS _cbtl_mj_inc)
  if(EXISTS "${_d}")
    list(APPEND _cbtl_mj_inc_ok "${_d}")
  endif()
endforeach()
set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_cbtl_mj_inc_ok}")

find_package(ompl REQUIRED)
# P2: OMPL_LIBRARIES names Boost dev symlinks that libompl-dev does not install; libompl.so already
# depends on the Boost runtime libraries, so absolute paths that do not exist are dropped.
set(_cbtl_ompl_libs)
foreach(_l IN LISTS OMPL_LIBRARIES)
  if(IS_ABSOLUTE "${_l}" AND NOT EXISTS "${_l}")
    continue()
  endif()
  list(APPEND _cbtl_ompl_libs "${_l}")
endforeach()
add_library(cbtl_ompl INTERFACE)
target_include_directories(cbtl_ompl SYSTEM INTERFACE ${OMPL_INCLUDE_DIRS})
target_link_libraries(cbtl_ompl INTERFACE ${_cbtl_ompl_libs})

find_package(fcl REQUIRED)                            # target "fcl" (no namespace)

# --- networking, storage, line editing ------------------------------------------------------------
find_package(CURL REQUIRED)
find_package(SQLite3 REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBEDIT REQUIRED IMPORTED_TARGET libedit)
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)
find_package(OpenSSL REQUIRED)                        # SHA-256 for the response cache
find_package(ZLIB REQUIRED)                           # the run record (gzip members), PNG pictures

# --- tests and benchmarks (not needed by `make demo`, which configures without them) ---------------------------
if(CBTL_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(CBTL_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
