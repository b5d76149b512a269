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
find_package(meshoptimizer REQUIRED CONFIG)
# Embree 3 (libembree-dev) casts the range sensors' rays against the static scene (src/sense/).
find_package(embree 3 REQUIRED CONFIG)

# three.js for the replay viewer (libjs-three, r111): its build and the non-module OrbitControls are inlined
# into every viewer file, so they are staged beside the viewer's own files.
find_file(PEG3D_THREE_JS three.min.js PATHS /usr/share/javascript/three NO_DEFAULT_PATH REQUIRED)
find_file(PEG3D_ORBIT_CONTROLS_JS OrbitControls.js PATHS /usr/share/javascript/three/examples/js/controls
          NO_DEFAULT_PATH REQUIRED)

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
