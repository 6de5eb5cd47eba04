#pragma once
// A synthetic lab test whose pulses are known exactly, and the CSV files shpb writes read back:
// the one set-up the `process` tests on lab records share (test_lab_data.cpp,
// test_process_reduction_choices.cpp, test_process.cpp, test_record_formats.cpp).
//
// Steel Kolsky bars (2 m, 20 mm) and a 5 mm specimen; the incident gauge 1 m and the transmitted
// gauge 0.5 m from the specimen; a record at 10 MHz over 800 µs.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_shpb.hpp"

namespace shpb_test {

inline constexpr double kDt = 1e-7;    // 10 MHz record
inline constexpr int kSamples = 8000;  // 800 µs

// A trapezoid of unit height starting at t0: `rise` up, flat, `rise` down, `length` long.
inline double trap(double t, double t0, double length = 100e-6, double rise = 10e-6) {
  const double u = t - t0;
  if (u <= 0 || u >= length) return 0.0;
  if (u < rise) return u / rise;
  if (u > length - rise) return (length - u) / rise;
  return 1.0;
}

// Gauge strains against time, tension positive. By default the clean test: incident −1e-3 at
// 50 µs (reaching the specimen at 250 µs), reflected +0.6e-3 back at 450 µs, transmitted
// −0.4e-3 at 350 µs; at the faces all three start at 250 µs.
struct Record {
  std::function<double(double)> incident_gauge = [](double t) {
    return -1e-3 * trap(t, 50e-6) + 0.6e-3 * trap(t, 450e-6);
  };
  std::function<double(double)> transmitted_gauge = [](double t) {
    return -0.4e-3 * trap(t, 350e-6);
  };
};

// The clean test with pulses of another rise time.
inline Record clean(double rise = 10e-6) {
  return {[=](double t) {
            return -1e-3 * trap(t, 50e-6, 100e-6, rise) + 0.6e-3 * trap(t, 450e-6, 100e-6, rise);
          },
          [=](double t) { return -0.4e-3 * trap(t, 350e-6, 100e-6, rise); }};
}

// The clean test broken 40 µs into the loading (faces' clock): the transmitted pulse falls to zero
// over 10 µs and stays there, while the reflected pulse rises to the whole incident pulse (the
// front force drops to zero) and the faces keep moving apart.
inline Record fractured() {
  Record rec;
  rec.incident_gauge = [](double t) {
    const double u = t - 450e-6;
    double refl = 0.6e-3 * trap(t, 450e-6);
    if (u > 40e-6) refl += 0.4e-3 * std::min(1.0, (u - 40e-6) / 10e-6) * trap(t, 450e-6);
    return -1e-3 * trap(t, 50e-6) + refl;
  };
  rec.transmitted_gauge = [](double t) {
    const double u = t - 350e-6;
    return -0.4e-3 * trap(t, 350e-6) * (u < 40e-6 ? 1.0 : std::max(0.0, 1 - (u - 40e-6) / 10e-6));
  };
  return rec;
}

// The record as a CSV file `time_s,incident,transmitted`, each strain times `scale`, on a clock
// that reads `clock_start` at the record's first sample (a DAQ's time since it was armed).
inline std::string csv(const Record& r, double scale = 1.0, double dt = kDt, int samples = kSamples,
                       double clock_start = 0) {
  std::ostringstream s;
  s.precision(17);
  s << "time_s,incident,transmitted\n";
  for (int i = 0; i < samples; ++i) {
    const double t = i * dt;
    s << clock_start + t << "," << scale * r.incident_gauge(t) << ","
      << scale * r.transmitted_gauge(t) << "\n";
  }
  return s.str();
}

// The bars above, measured by `signals.csv` beside the scene (strain columns by name).
inline nlohmann::json steel_scene() {
  return nlohmann::json::parse(R"({
  "bars": [
    { "name": "striker", "material": "steel", "length": "200 mm", "diameter": "20 mm", "velocity": "10 m/s" },
    { "name": "incident", "material": "steel", "length": "2 m", "diameter": "20 mm",
      "gauges": [ { "name": "incident", "position": "1 m" } ] },
    { "name": "specimen", "material": "soft", "length": "5 mm", "diameter": "10 mm" },
    { "name": "transmitter", "material": "steel", "length": "2 m", "diameter": "20 mm",
      "gauges": [ { "name": "transmitted", "position": "0.5 m" } ] }
  ],
  "specimen": "specimen",
  "materials": {
    "steel": { "model": "elastic", "density": 8000, "youngs_modulus": "200 GPa", "poisson_ratio": 0.29 },
    "soft": { "model": "elastic", "density": 2700, "youngs_modulus": "70 GPa", "poisson_ratio": 0.33 }
  },
  "measurement": {
    "file": "signals.csv", "time": { "column": "time_s", "unit": "s" },
    "channels": [ { "gauge": "incident", "column": "incident", "unit": "strain" },
                  { "gauge": "transmitted", "column": "transmitted", "unit": "strain" } ],
    "dispersion": { "correction": "none" }
  }
})");
}

// Writes dir/signals.csv and dir/scene.json; returns the scene's path.
inline std::filesystem::path write(const std::filesystem::path& dir, const nlohmann::json& scene,
                                   const std::string& signals) {
  std::ofstream(dir / "signals.csv") << signals;
  std::ofstream(dir / "scene.json") << scene.dump(2);
  return dir / "scene.json";
}

inline nlohmann::json summary(const std::filesystem::path& out) {
  return nlohmann::json::parse(read_text(out / "summary.json"));
}

inline bool has_warning(const nlohmann::json& s, const std::string& text) {
  for (const auto& w : s["warnings"])
    if (w.get<std::string>().find(text) != std::string::npos) return true;
  return false;
}

// The columns of a CSV file (header + numbers, comma separated).
inline std::vector<std::vector<double>> read_columns(const std::filesystem::path& file) {
  std::istringstream in(read_text(file));
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::istringstream f(line);
    std::string v;
    for (std::size_t c = 0; std::getline(f, v, ','); ++c) {
      if (cols.size() <= c) cols.emplace_back();
      cols[c].push_back(std::strtod(v.c_str(), nullptr));  // subnormals too
    }
  }
  return cols;
}

// A CSV file written by shpb or by these tests: the header's names and the columns.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  const std::vector<double>& operator[](const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    REQUIRE(it != names.end());
    return columns[static_cast<std::size_t>(it - names.begin())];
  }
};

inline Table read_table(const std::filesystem::path& file) {
  Table t;
  std::istringstream in(read_text(file));
  std::string line, cell;
  std::getline(in, line);
  for (std::istringstream h(line); std::getline(h, cell, ',');) t.names.push_back(cell);
  t.columns = read_columns(file);
  t.columns.resize(t.names.size());
  return t;
}

// Rows [0, rows) taking every `step`-th, written with 17 digits.
inline void write_table(const std::filesystem::path& file, const Table& t, std::size_t step = 1) {
  std::ofstream out(file);
  out.precision(17);
  for (std::size_t c = 0; c < t.names.size(); ++c) out << (c ? "," : "") << t.names[c];
  out << "\n";
  for (std::size_t i = 0; i < t.columns[0].size(); i += step) {
    for (std::size_t c = 0; c < t.names.size(); ++c) out << (c ? "," : "") << t.columns[c][i];
    out << "\n";
  }
}

}  // namespace shpb_test
