# All dependencies are Debian 12 packages (see tools/deps.sh); nothing is downloaded or vendored.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.11 REQUIRED)
find_package(assimp REQUIRED)
find_package(octomap REQUIRED)
find_package(dynamicEDT3D REQUIRED)

# Debian's BulletConfig.cmake carries relative paths; its pkg-config file is reliable. peg3d uses the
# double-precision build so that sweep fractions and contact points keep the precision of the rest of the
# code (all geometry is double).
pkg_check_modules(BULLET REQUIRED IMPORTED_TARGET bullet-float64)

if(PEG3D_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(PEG3D_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
