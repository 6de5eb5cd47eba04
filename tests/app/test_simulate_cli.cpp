// `shpb simulate` as a user sees it: bad input is exit 2 with one error line and nothing written.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

TEST_CASE("Simulating a scene that cannot be read exits with 2 and writes nothing", "[app][simulate]") {
  const fs::path dir = fs::temp_directory_path() / "shpb_test_simulate_missing";
  fs::remove_all(dir);
  const std::string cmd = std::string(SHPB_EXE) + " simulate " +
                          (fs::temp_directory_path() / "no_such_scene.json").string() + " -o " +
                          dir.string() + " --quiet 2>/dev/null";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 2);
  CHECK_FALSE(fs::exists(dir));
}
