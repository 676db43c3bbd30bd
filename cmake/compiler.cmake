# Compiler settings shared by every target (added through svmp_settings).
add_library(svmp_settings INTERFACE)
# Includes are written from the repository root ("svm/kernel.hpp"); installed, from include/svmp.
target_include_directories(svmp_settings INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                                   $<INSTALL_INTERFACE:include/svmp>)
# The headers need C++20; a project linking the installed package gets it with them.
target_compile_features(svmp_settings INTERFACE cxx_std_20)
target_compile_options(svmp_settings INTERFACE $<BUILD_INTERFACE:-Wall -Wextra -Wpedantic -Wno-unused-parameter>)
if(SVMP_NATIVE)
  target_compile_options(svmp_settings INTERFACE -march=native)
endif()
if(SVMP_SANITIZE)
  # Under ASan Eigen stops trusting malloc's 16-byte alignment and allocates by hand, while the
  # unsanitized libompl does not: matrices crossing between them (OMPL's projections) would be freed
  # with the wrong function. glibc's and ASan's malloc are 16-byte aligned, so keep Eigen on malloc.
  target_compile_definitions(svmp_settings INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=1)
  target_compile_options(svmp_settings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(svmp_settings INTERFACE -fsanitize=address,undefined)
endif()
