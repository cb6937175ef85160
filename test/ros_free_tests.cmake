# The gtests of the ROS-free libraries, shared by the catkin build and the standalone one
# (cmake/ros_free). Each includer defines enhanced_orb_add_gtest(target source) and sets
# ENHANCED_ORB_GTEST_MAIN, ENHANCED_ORB_EUROC_DIR and ENHANCED_ORB_MOVING_DIR.
foreach(unit params enhance noise adaptive_threshold orb_extractor degenerate draw concurrency)
  enhanced_orb_add_gtest(test_${unit} ${ENHANCED_ORB_ROOT}/test/unit/test_${unit}.cpp)
  target_link_libraries(test_${unit} enhanced_orb_core ${OpenCV_LIBRARIES} ${ENHANCED_ORB_GTEST_MAIN})
  target_compile_definitions(test_${unit} PRIVATE ENHANCED_ORB_EUROC_DIR="${ENHANCED_ORB_EUROC_DIR}")
endforeach()
target_include_directories(test_concurrency PRIVATE ${ENHANCED_ORB_ROOT}/src/core)  # parallel.h
# The extractor against its reference; it reads the kernels' internal header.
enhanced_orb_add_gtest(test_identity ${ENHANCED_ORB_ROOT}/test/unit/test_identity.cpp)
target_link_libraries(test_identity enhanced_orb_core ${OpenCV_LIBRARIES} ${ENHANCED_ORB_GTEST_MAIN})
target_include_directories(test_identity PRIVATE ${ENHANCED_ORB_ROOT}/src/core)
target_compile_definitions(test_identity PRIVATE ENHANCED_ORB_EUROC_DIR="${ENHANCED_ORB_EUROC_DIR}")
enhanced_orb_kernel_definitions(test_identity)
# The drop-in adapters (cv::Feature2D, ORB-SLAM's extractor); they read the package's config files.
enhanced_orb_add_gtest(test_adapters ${ENHANCED_ORB_ROOT}/test/unit/test_adapters.cpp)
target_link_libraries(test_adapters enhanced_orb_core ${OpenCV_LIBRARIES} ${ENHANCED_ORB_GTEST_MAIN})
target_compile_definitions(test_adapters PRIVATE ENHANCED_ORB_EUROC_DIR="${ENHANCED_ORB_EUROC_DIR}"
  ENHANCED_ORB_SOURCE_DIR="${ENHANCED_ORB_ROOT}")
enhanced_orb_add_gtest(test_evaluation ${ENHANCED_ORB_ROOT}/test/unit/test_evaluation.cpp)
target_link_libraries(test_evaluation enhanced_orb_evaluation ${ENHANCED_ORB_GTEST_MAIN})
enhanced_orb_add_gtest(test_sequence ${ENHANCED_ORB_ROOT}/test/unit/test_sequence.cpp)
target_link_libraries(test_sequence enhanced_orb_evaluation ${ENHANCED_ORB_GTEST_MAIN})
target_compile_definitions(test_sequence PRIVATE ENHANCED_ORB_MOVING_DIR="${ENHANCED_ORB_MOVING_DIR}")
# Camera motion judged from a stream, and the extractors that follow it.
enhanced_orb_add_gtest(test_camera_motion ${ENHANCED_ORB_ROOT}/test/unit/test_camera_motion.cpp)
target_link_libraries(test_camera_motion enhanced_orb_evaluation ${ENHANCED_ORB_GTEST_MAIN})
# The lighting sets and the KITTI excerpts sit beside the EuRoC excerpts in ../shared/data.
get_filename_component(ENHANCED_ORB_SHARED_DATA "${ENHANCED_ORB_EUROC_DIR}/../.." ABSOLUTE)
target_compile_definitions(test_camera_motion PRIVATE ENHANCED_ORB_EUROC_DIR="${ENHANCED_ORB_EUROC_DIR}"
  ENHANCED_ORB_MOVING_DIR="${ENHANCED_ORB_MOVING_DIR}" ENHANCED_ORB_SHARED_DATA="${ENHANCED_ORB_SHARED_DATA}")
# Allocations per frame of a camera's stream, either selection (the benchmark's counter replaces
# operator new: a binary of its own).
enhanced_orb_add_gtest(test_allocations ${ENHANCED_ORB_ROOT}/test/unit/test_allocations.cpp
  ${ENHANCED_ORB_ROOT}/bench/allocation_count.cpp)
target_include_directories(test_allocations PRIVATE ${ENHANCED_ORB_ROOT}/bench)
target_link_libraries(test_allocations enhanced_orb_core ${OpenCV_LIBRARIES} ${ENHANCED_ORB_GTEST_MAIN})
target_compile_definitions(test_allocations PRIVATE ENHANCED_ORB_EUROC_DIR="${ENHANCED_ORB_EUROC_DIR}"
  ENHANCED_ORB_MOVING_DIR="${ENHANCED_ORB_MOVING_DIR}")
