# SPDX-License-Identifier: MIT
# cmake -P script behind the consumer test: install, configure, build, run.
foreach(var BUILD_DIR WORK_DIR PROJECT_DIR GENERATOR CXX_COMPILER PVS_FILE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake: ${var} not set")
  endif()
endforeach()
if(NOT CONFIG)
  set(CONFIG Release)
endif()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

# What `cmake --install BUILD --prefix PREFIX` does, restricted to the urbanpvs package: the
# top-level install script holds the package rules (cmake/UrbanpvsPackage.cmake: library,
# headers, export set, config files) and runtime/tools' script the tool. CMAKE_INSTALL_LOCAL_ONLY
# keeps the scripts of the other folders out, whose programs this test does not build.
foreach(script ${BUILD_DIR}/cmake_install.cmake ${BUILD_DIR}/runtime/tools/cmake_install.cmake)
  execute_process(COMMAND ${CMAKE_COMMAND} -DCMAKE_INSTALL_PREFIX=${prefix}
                          -DCMAKE_INSTALL_CONFIG_NAME=${CONFIG} -DCMAKE_INSTALL_LOCAL_ONLY=ON
                          -P ${script}
                  COMMAND_ERROR_IS_FATAL ANY)
endforeach()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
          -DCMAKE_BUILD_TYPE=${CONFIG}
          -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
          "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
          "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}"
          -DCMAKE_PREFIX_PATH=${prefix}
          -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
          -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON
  COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build --config ${CONFIG}
                COMMAND_ERROR_IS_FATAL ANY)
find_program(consumer urbanpvs_consumer PATHS ${WORK_DIR}/build ${WORK_DIR}/build/${CONFIG}
             NO_DEFAULT_PATH REQUIRED)
execute_process(COMMAND ${consumer} ${PVS_FILE} COMMAND_ERROR_IS_FATAL ANY)
# The installed tool runs too.
find_program(inspect urbanpvs-inspect PATHS ${prefix}/bin NO_DEFAULT_PATH REQUIRED)
execute_process(COMMAND ${inspect} ${PVS_FILE} --cell 2 OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
