#pragma once
// The Pareto front of accuracy against cost: a run is on the front when no other run is at least
// as accurate and at least as cheap, and strictly better in one of the two.
#include <optional>
#include <vector>

namespace shpb {

// front[i] is true when point i (error[i], cost[i]) is not dominated. Points with a non-finite
// error (unstable runs) are never on the front and dominate nothing.
std::vector<bool> pareto_front(const std::vector<double>& error, const std::vector<double>& cost);

// Cost of a curve at a given error, interpolated linearly in log(error)–log(cost) between the
// two points of (errors, costs) that bracket it; nullopt outside their range.
std::optional<double> cost_at_error(std::vector<double> errors, std::vector<double> costs,
                                    double error);

}  // namespace shpb
