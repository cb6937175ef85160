# The ROS-free libraries, shared by the catkin build (CMakeLists.txt) and the standalone one
# (cmake/ros_free/CMakeLists.txt, which scripts/aarch64.sh cross-builds): enhanced_orb_core, the
# method, and enhanced_orb_evaluation. Expects ENHANCED_ORB_ROOT, WARNINGS and OpenCV_LIBRARIES.

# The extraction kernels (src/core/kernels) are built once per instruction set and chosen at run
# time (include/enhanced_orb/simd.h): on x86-64 SSE2 and AVX2, on aarch64 NEON.
# ENHANCED_ORB_PORTABLE=ON builds the scalar and 16-byte kernels only, for any CPU the compiler targets.
option(ENHANCED_ORB_PORTABLE "Build only the portable extraction kernels (no AVX2)" OFF)
set(ENHANCED_ORB_KERNELS_DIR ${ENHANCED_ORB_ROOT}/src/core/kernels)
set(CORE_KERNELS ${ENHANCED_ORB_KERNELS_DIR}/fast_score_scalar.cpp ${ENHANCED_ORB_KERNELS_DIR}/fast_score_vector128.cpp
  ${ENHANCED_ORB_KERNELS_DIR}/suppression_scalar.cpp ${ENHANCED_ORB_KERNELS_DIR}/pyramid_rows_scalar.cpp
  ${ENHANCED_ORB_KERNELS_DIR}/rotated_offsets_scalar.cpp ${ENHANCED_ORB_KERNELS_DIR}/table_lookup_scalar.cpp
  ${ENHANCED_ORB_KERNELS_DIR}/patch_moments_scalar.cpp)
set(ENHANCED_ORB_X86_KERNELS OFF)
set(ENHANCED_ORB_NEON_KERNELS OFF)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "aarch64|arm64|ARM64")
  # NEON (with fused multiply-add) is part of every aarch64 CPU: its kernels are the 16-byte level.
  set(ENHANCED_ORB_NEON_KERNELS ON)
  list(APPEND CORE_KERNELS ${ENHANCED_ORB_KERNELS_DIR}/suppression_neon.cpp
    ${ENHANCED_ORB_KERNELS_DIR}/pyramid_rows_neon.cpp)
else()
  list(APPEND CORE_KERNELS ${ENHANCED_ORB_KERNELS_DIR}/suppression_vector128.cpp
    ${ENHANCED_ORB_KERNELS_DIR}/pyramid_rows_vector128.cpp)
endif()
if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64" AND NOT ENHANCED_ORB_PORTABLE)
  set(ENHANCED_ORB_X86_KERNELS ON)
  set(X86_KERNELS_AVX2 ${ENHANCED_ORB_KERNELS_DIR}/fast_score_avx2.cpp ${ENHANCED_ORB_KERNELS_DIR}/suppression_avx2.cpp
    ${ENHANCED_ORB_KERNELS_DIR}/pyramid_rows_avx2.cpp ${ENHANCED_ORB_KERNELS_DIR}/rotated_offsets_avx2.cpp
    ${ENHANCED_ORB_KERNELS_DIR}/table_lookup_avx2.cpp ${ENHANCED_ORB_KERNELS_DIR}/otsu_avx2.cpp
    ${ENHANCED_ORB_KERNELS_DIR}/patch_moments_avx2.cpp)
  set_source_files_properties(${X86_KERNELS_AVX2} PROPERTIES COMPILE_OPTIONS "-mavx2;-mfma")
  list(APPEND CORE_KERNELS ${X86_KERNELS_AVX2})
endif()

# Which kernel sets this build has, as compile definitions of `target` (the library's dispatch and
# the tests that compare the kernels read them).
function(enhanced_orb_kernel_definitions target)
  foreach(kernels X86 NEON)
    if(ENHANCED_ORB_${kernels}_KERNELS)
      target_compile_definitions(${target} PRIVATE ENHANCED_ORB_${kernels}_KERNELS)
    endif()
  endforeach()
endfunction()

# The method, free of ROS: what nodelets, tools, benchmarks and tests share.
add_library(enhanced_orb_core
  ${ENHANCED_ORB_ROOT}/src/core/camera_motion.cpp
  ${ENHANCED_ORB_ROOT}/src/core/noise.cpp
  ${ENHANCED_ORB_ROOT}/src/core/params.cpp
  ${ENHANCED_ORB_ROOT}/src/core/simd.cpp
  ${ENHANCED_ORB_ROOT}/src/core/enhance.cpp
  ${ENHANCED_ORB_ROOT}/src/core/adaptive_threshold.cpp
  ${ENHANCED_ORB_ROOT}/src/core/pyramid.cpp
  ${ENHANCED_ORB_ROOT}/src/core/corners.cpp
  ${ENHANCED_ORB_ROOT}/src/core/selection.cpp
  ${ENHANCED_ORB_ROOT}/src/core/orientation.cpp
  ${ENHANCED_ORB_ROOT}/src/core/orb_extractor.cpp
  ${ENHANCED_ORB_ROOT}/src/core/feature2d.cpp
  ${ENHANCED_ORB_ROOT}/src/core/orb_slam_extractor.cpp
  ${ENHANCED_ORB_ROOT}/src/core/linear_resize.cpp
  ${ENHANCED_ORB_ROOT}/src/core/rbrief.cpp
  ${ENHANCED_ORB_ROOT}/src/core/draw.cpp
  ${CORE_KERNELS}
)
target_include_directories(enhanced_orb_core PRIVATE ${ENHANCED_ORB_ROOT}/src/core)
# No fused multiply-add where the source has none: the descriptor pattern's rotation rounds as the
# installed cv::ORB does (rbrief.cpp decides how), whatever instruction set a file is built for.
target_compile_options(enhanced_orb_core PRIVATE ${WARNINGS} -ffp-contract=off)
enhanced_orb_kernel_definitions(enhanced_orb_core)
target_link_libraries(enhanced_orb_core ${OpenCV_LIBRARIES})

# The evaluation, free of ROS: dataset reader, degradations, the compared methods, metrics.
add_library(enhanced_orb_evaluation
  ${ENHANCED_ORB_ROOT}/src/evaluation/dataset.cpp
  ${ENHANCED_ORB_ROOT}/src/evaluation/degrade.cpp
  ${ENHANCED_ORB_ROOT}/src/evaluation/files.cpp
  ${ENHANCED_ORB_ROOT}/src/evaluation/methods.cpp
  ${ENHANCED_ORB_ROOT}/src/evaluation/metrics.cpp
  ${ENHANCED_ORB_ROOT}/src/evaluation/orb_slam_style.cpp
  ${ENHANCED_ORB_ROOT}/src/evaluation/sequence.cpp
)
target_compile_options(enhanced_orb_evaluation PRIVATE ${WARNINGS})
target_link_libraries(enhanced_orb_evaluation enhanced_orb_core ${OpenCV_LIBRARIES})
