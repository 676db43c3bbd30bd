# `cmake --install build --prefix P` installs the libraries, their headers (under include/svmp, included
# as "svm/kernel.hpp" and so on) and a package config, so another CMake project can do
#   find_package(svmp REQUIRED)   # with CMAKE_PREFIX_PATH=P
#   target_link_libraries(app PRIVATE svmp::svm)   # or svmp::robots, svmp::cspace, svmp::planners
# svmp::planners links the planners' archive whole, so every registered planner is in the program.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(svmp_exported svmp_settings svmp_robots svmp_svm svmp_cspace svmp_planners_objects svmp_planners)
if(SVMP_WITH_OMPL)
  list(APPEND svmp_exported ompl_bridge_deps svmp_ompl)
endif()
foreach(target ${svmp_exported})
  string(REGEX REPLACE "^svmp_" "" name ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
endforeach()
install(TARGETS ${svmp_exported} EXPORT svmpTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY robots svm cspace planners DESTINATION include/svmp FILES_MATCHING PATTERN "*.hpp")
install(EXPORT svmpTargets NAMESPACE svmp:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/svmp)
configure_package_config_file(cmake/svmpConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/svmpConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/svmp)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/svmpConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/svmpConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/svmpConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/svmp)

# The install works for another project: install into the build tree, build examples/consumer against
# it and plan with it.
if(SVMP_BUILD_TESTS)
  set(prefix ${CMAKE_CURRENT_BINARY_DIR}/install_test)
  set(ompl_example "")
  if(SVMP_WITH_OMPL)  # the OMPL example on its own against the package, as the README builds it
    set(ompl_example " && cmake -S '${PROJECT_SOURCE_DIR}/examples/ompl' -B '${prefix}/ompl' -DCMAKE_PREFIX_PATH='${prefix}/usr' -DCMAKE_BUILD_TYPE=Release >/dev/null && cmake --build '${prefix}/ompl' >/dev/null && '${prefix}/ompl/svmp-ompl-example' '${PROJECT_SOURCE_DIR}/bench/scenarios/thesis_fig3_5.yaml' >/dev/null")
  endif()
  add_test(NAME install_and_find_package
           COMMAND sh -c "rm -rf '${prefix}' && cmake --install '${CMAKE_BINARY_DIR}' --prefix '${prefix}/usr' >/dev/null && cmake -S '${PROJECT_SOURCE_DIR}/examples/consumer' -B '${prefix}/build' -DCMAKE_PREFIX_PATH='${prefix}/usr' -DCMAKE_BUILD_TYPE=Release >/dev/null && cmake --build '${prefix}/build' >/dev/null && '${prefix}/build/consumer' '${PROJECT_SOURCE_DIR}/bench/scenarios/thesis_fig3_5.yaml' svmp ompl-rrtconnect${ompl_example}")
  set_tests_properties(install_and_find_package PROPERTIES TIMEOUT 600)
endif()
