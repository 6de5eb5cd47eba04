#pragma once
// The one way a test that cannot run here stops: it says why, and ctest counts it as skipped (its
// output holds "SKIPPED:", CMakeLists.txt SKIP_REGULAR_EXPRESSION), never as passed.
#include <catch2/catch.hpp>

#define SHPB_SKIP(reason)          \
  do {                             \
    WARN("SKIPPED: " << (reason)); \
    return;                        \
  } while (false)
