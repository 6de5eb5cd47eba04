#include "study/pareto_front.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/interpolation.hpp"

namespace shpb {

std::vector<bool> pareto_front(const std::vector<double>& error, const std::vector<double>& cost) {
  const std::size_t n = error.size();
  std::vector<bool> front(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j)
      dominated = j != i && std::isfinite(error[j]) && error[j] <= error[i] && cost[j] <= cost[i] &&
                  (error[j] < error[i] || cost[j] < cost[i]);
    front[i] = !dominated;
  }
  return front;
}

std::optional<double> cost_at_error(std::vector<double> errors, std::vector<double> costs,
                                    double error) {
  std::vector<std::size_t> order(errors.size());
  std::iota(order.begin(), order.end(), 0);
  std::erase_if(order, [&](std::size_t i) { return !(errors[i] > 0) || !(costs[i] > 0); });
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return errors[a] < errors[b]; });
  for (std::size_t k = 0; k + 1 < order.size(); ++k) {
    const double e0 = errors[order[k]], e1 = errors[order[k + 1]];
    if (error < e0 || error > e1) continue;
    if (e0 == e1) return costs[order[k]];
    const double w = std::log(error / e0) / std::log(e1 / e0);
    return std::exp(lerp(std::log(costs[order[k]]), std::log(costs[order[k + 1]]), w));
  }
  return std::nullopt;
}

}  // namespace shpb
