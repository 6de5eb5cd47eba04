// `shpb process SCENE -o DIR [--signals FILE]` (docs/commands.md, docs/outputs.md): gauge signals →
// pulses at the specimen faces → 1/2/3-wave stress–strain curves (analysis/process_scene.hpp),
// written by analysis/process_outputs.hpp. Everything is read and checked before the output
// folder is created.
#include "app/process.hpp"

#include <malloc.h>

#include <cstdio>
#include <memory>

#include "analysis/process_campaign.hpp"
#include "app/cli_options.hpp"
#include "app/commands.hpp"
#include "core/error.hpp"

namespace shpb {
namespace {

void reuse_heap_buffers() {
  // A long record passes through buffers of tens of MB (file, fields, columns, FFT): taken from
  // the heap and, once freed, reused instead of returned to the kernel and faulted in again
  // (1 M-row record: 70 700 -> 40 400 page faults, system time 0.17 -> 0.08 s). A glibc that
  // refuses the values keeps its defaults.
  constexpr int kHeapBuffers = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kHeapBuffers);
  mallopt(M_TRIM_THRESHOLD, kHeapBuffers);
}

}  // namespace

int run_process(const ProcessArgs& args) {
  require_valid(args.monte_carlo);  // an option before the scene's own errors
  reuse_heap_buffers();
  const ProcessedScene p = process_into(args.scene, args.signals, args.output, &args.monte_carlo);
  if (args.quiet) return 0;
  const std::string headline =
      p.bars ? bar_check_headline(*p.bars, args.output) : process_headline(*p.outcome, args.output);
  std::fprintf(stderr, "%s\n", headline.c_str());
  return 0;
}

Command add_process_command(CLI::App& app) {
  struct Options {
    ProcessArgs one;
    CampaignOptions campaign;
    std::vector<std::string> scenes;
    std::string campaign_file, signals;
  };
  auto o = std::make_shared<Options>();
  CampaignOptions& campaign = o->campaign;
  auto* cmd = app.add_subcommand(
      "process",
      "Reduce gauge signals (the scene's measurement, or --signals) to aligned pulses "
      "and 1/2/3-wave stress–strain curves; write raw_signals.csv, pulses.csv, curve.csv, "
      "summary.json (several tests: a folder each, campaign.csv and summary.json)");
  cmd->add_option("scene", o->scenes,
                  "Scene JSON file (bars, gauges, specimen, measurement); several: a "
                  "campaign, one folder per test and campaign.csv");
  cmd->add_option("--campaign", o->campaign_file,
                  "Campaign file (tests[]: {scene, name}) instead of scenes: one folder per "
                  "test and campaign.csv");
  cmd->add_option("--flow-stress-at", campaign.flow_strains,
                  "Campaigns: engineering strains at which campaign.csv gives the flow "
                  "stress, e.g. 0.02,0.05")
      ->delimiter(',');
  cmd->add_option("--shard", campaign.shard,
                  "Campaigns: process every N-th test from K into DIR/parts/K-of-N (K/N)");
  cmd->add_flag("--merge", campaign.merge,
                "Campaigns: check DIR/parts holds every test once; write DIR/result");
  cmd->add_option("-o,--output", o->one.output, "Output folder (replaced atomically)")->required();
  cmd->add_option("--signals", o->signals,
                  "Gauge signals to process instead of the scene's measurement, e.g. a "
                  "gauges.csv written by `shpb simulate`");
  cmd->add_flag("--quiet,-q", o->one.quiet, "No progress output on stderr");
  auto* draws = cmd->add_option("--draws", o->one.monte_carlo.draws,
                                "Monte Carlo draws of measurement.uncertainty (default 1000)")
                    ->check(unsigned_text_check());
  // Its range: MonteCarloOptions::IsValid, checked before the scene is read (run_process,
  // process_campaign), as the Python module checks it.
  auto* seed =
      add_seed_option(cmd, o->one.monte_carlo.seed,
                      "Seed of the Monte Carlo draws (default 1: the same draws every run)");
  add_threads_option(cmd, o->one.monte_carlo.threads,
                     "Worker threads of the Monte Carlo draws (0 = all cores)");
  return {cmd, [o, draws, seed] {
            CampaignOptions& c = o->campaign;
            const bool several = o->scenes.size() != 1 || !o->campaign_file.empty() ||
                                 !c.shard.empty() || c.merge || !c.flow_strains.empty();
            if (several) {
              if (!o->signals.empty())
                throw input_error("--signals", "", "", "processes one scene: not with a campaign");
              for (const auto& s : o->scenes) c.scenes.push_back(s);
              if (!o->campaign_file.empty()) c.campaign = o->campaign_file;
              c.output = o->one.output;
              // As given: a merge refuses draws it cannot make (CampaignOptions::IsValid).
              if (draws->count() > 0) c.draws = o->one.monte_carlo.draws;
              if (seed->count() > 0) c.seed = o->one.monte_carlo.seed;
              c.threads = o->one.monte_carlo.threads;
              if (!o->one.quiet)
                c.progress = [](const std::string& l) {
                  std::fprintf(stderr, "process: %s\n", l.c_str());
                };
              reuse_heap_buffers();
              process_campaign(c);
              return 0;
            }
            o->one.scene = o->scenes.front();
            if (!o->signals.empty()) o->one.signals = o->signals;
            return run_process(o->one);
          }};
}

}  // namespace shpb
