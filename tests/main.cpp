// Catch2 v2 main, compiled once (the other test files only include the header).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
