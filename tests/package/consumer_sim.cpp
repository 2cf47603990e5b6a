// l2scalib::sim from outside: one simulated sweep of the paper's setting 1.
#include <l2s/sim/simulation.hpp>

#include <cstdio>

int main() {
  auto config = l2s::sim::SimulationConfig::paper(1, "vlp16");
  config.frames = 1;
  const l2s::sim::DatasetSimulator simulator(config);
  const l2s::LidarCloud sweep = simulator.sweep(0);
  std::printf("simulated sweep: %zu points\n", sweep.size());
  return sweep.size() > 1000 ? 0 : 1;
}
