// The guard of the tests that read the shared data.
#ifndef ENHANCED_ORB_TEST_SHARED_DATA_H
#define ENHANCED_ORB_TEST_SHARED_DATA_H

#include <cstdlib>

#include <gtest/gtest.h>

// The guard of every test that reads the shared data (../shared): when `present` is false the test
// is skipped, or fails instead under ENHANCED_ORB_REQUIRE_DATA (which the test command sets), saying
// what was not found. A statement for the body of a TEST.
#define REQUIRE_SHARED_DATA(present, what)                                   \
  do {                                                                       \
    if (!(present)) {                                                        \
      if (std::getenv("ENHANCED_ORB_REQUIRE_DATA")) {                        \
        FAIL() << (what) << " not found (ENHANCED_ORB_REQUIRE_DATA is set)"; \
      }                                                                      \
      GTEST_SKIP() << (what) << " not found (../shared absent): skipped";    \
    }                                                                        \
  } while (false)

#endif  // ENHANCED_ORB_TEST_SHARED_DATA_H
