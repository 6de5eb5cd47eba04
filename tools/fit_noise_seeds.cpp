// Scatter of the synthetic fit over noise draws (docs/methods.md §9, "Standard errors"): the fit's
// recovery campaign (tests/fit/synthetic_scene.hpp: three simulated OFHC copper tests, 1 % noise,
// A, B, n, C started 20 % off) is drawn with N seeds and fitted through the executable; per seed it
// prints each parameter's (estimate − truth)/std_error and its relative error, then how many seeds
// meet the tolerances (A, B, n 3 %, C 10 %), how many have all four within two standard errors and
// the RMS of each z over the seeds (1 if the standard errors are right).
// With --al6061 the campaign is the Al 6061-T6 one of docs/validation.md (shpb fit, "A second
// law"): truth specimens/al6061-t6.json with B 10 % above the file's, the file itself the start,
// A, B, n free and each test's striker velocity (±5 %), C fixed; global stepping by default.
// Build: cmake --build build --target fit_noise_seeds shpb; run:
//   build/fit_noise_seeds [--seeds N] [--first SEED] [--stepping asynchronous|global]
//                         [--filter DURATION] [--keep DIR] [--al6061 1]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../tests/fit/synthetic_scene.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

int main(int argc, char** argv) {
  int seeds = 8;
  unsigned first = 3000;  // the recovery test draws 2024, 2025, 2026
  std::string stepping, filter = "1 us";
  fs::path keep;
  bool al = false;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--seeds")
      seeds = std::stoi(v);
    else if (a == "--first")
      first = static_cast<unsigned>(std::stoul(v));
    else if (a == "--stepping")
      stepping = v;
    else if (a == "--filter")
      filter = v;
    else if (a == "--keep")
      keep = v;
    else if (a == "--al6061")
      al = v == "1";
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (stepping.empty()) stepping = al ? "global" : "asynchronous";
  const fs::path copper = fs::path(SHPB_SOURCE_DIR) / "specimens/ofhc-copper.json";
  const fs::path aluminium = fs::path(SHPB_SOURCE_DIR) / "specimens/al6061-t6.json";
  const char* names[] = {"A", "B", "n", "C"};
  const int count = al ? 3 : 4;  // C is fixed in the Al campaign
  const double truth[] = {al ? shpb_test::kAlTruthA : shpb_test::kTruthA,
                          al ? shpb_test::kAlTruthB : shpb_test::kTruthB,
                          al ? shpb_test::kAlTruthN : shpb_test::kTruthN, shpb_test::kTruthC};
  double z2[4] = {0, 0, 0, 0};
  int within = 0, done = 0, close = 0;
  std::printf("%6s %26s   %30s  %s\n", "seed", "z = (fit - truth)/std_error", "relative error (%)",
              "all |z|<=2");
  for (int s = 0; s < seeds; ++s) {
    const unsigned seed = first + 10 * static_cast<unsigned>(s);
    const fs::path dir = (keep.empty() ? fs::temp_directory_path() / "fit_noise_seeds" : keep) /
                         ("seed" + std::to_string(seed));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path campaign =
        al ? shpb_test::write_al6061_campaign(dir, aluminium, filter, stepping, seed)
           : shpb_test::write_synthetic_campaign(dir, copper, filter, stepping, seed);
    const std::string cmd = std::string("'") + SHPB_EXE + "' fit '" + campaign.string() + "' -o '" +
                            (dir / "out").string() + "' --threads 2 -q --bootstrap 0 2>/dev/null";
    if (std::system(cmd.c_str()) != 0) {
      std::printf("%6u fit failed\n", seed);
      continue;
    }
    const json sum = json::parse(std::ifstream(dir / "out/summary.json"));
    double z[4] = {0, 0, 0, 0}, off[4] = {0, 0, 0, 0};
    bool all = true;
    for (int p = 0; p < count; ++p) {
      const json& e = sum["parameters"][names[p]];
      const double value = e["value"];
      const double err = e["std_error"].is_number() ? e["std_error"].get<double>() : NAN;
      z[p] = (value - truth[p]) / err;
      off[p] = 100 * (value / truth[p] - 1);
      all = all && std::abs(z[p]) <= 2;
      z2[p] += z[p] * z[p];
    }
    within += all;
    // The acceptance's tolerances: A, B, n within 3 %, C within 10 %.
    close += std::abs(off[0]) <= 3 && std::abs(off[1]) <= 3 && std::abs(off[2]) <= 3 &&
             std::abs(off[3]) <= 10;
    ++done;
    std::printf(
        "%6u  A %+5.2f B %+5.2f n %+5.2f C %+5.2f   A %+5.2f B %+5.2f n %+5.2f C %+5.2f  %s\n",
        seed, z[0], z[1], z[2], z[3], off[0], off[1], off[2], off[3], all ? "yes" : "no");
    if (keep.empty()) fs::remove_all(dir);
  }
  std::printf("A, B, n within 3 %% and C within 10 %%: %d of %d\n", close, done);
  std::printf("all four within 2 std errors: %d of %d; RMS z: A %.2f B %.2f n %.2f C %.2f\n",
              within, done, std::sqrt(z2[0] / done), std::sqrt(z2[1] / done),
              std::sqrt(z2[2] / done), std::sqrt(z2[3] / done));
  return 0;
}
