// Cost of one force evaluation per model (Google Benchmark), on Gladkyy's W11 bridge: the
// per-bridge invariants are computed once, as in the Law2; the gaps cover [0, rupture) evenly, in a
// seeded random order (as the bridges of a packing come in the Law2: no branch is predictable).
// The exact solver is timed per solve on an existing bridge (its branch already followed), and the
// bridge's creation (make_bridge: validation, invariants; for young_laplace_table the interpolation
// of its curve in the table and its Hermite segments) per model as "<name>/make".
#include "models.hpp"
#include "young_laplace.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

using namespace capillary;

namespace {
BridgeSpec w11(Model m)
{
	BridgeSpec s;
	s.R1 = s.R2 = 2.381e-3, s.volume = 13.6e-12, s.gamma = 20.6e-3, s.model = m;
	return s;
}

void model_force(benchmark::State& state, Model m)
{
	const Bridge        b = make_bridge(w11(m));
	std::vector<double> gaps(1024);
	for (size_t i = 0; i < gaps.size(); ++i) gaps[i] = b.rupture * (i + 0.5) / gaps.size();
	std::shuffle(gaps.begin(), gaps.end(), std::mt19937(1));
	size_t i = 0;
	for (auto _ : state) {
		benchmark::DoNotOptimize(bridge_force(b, gaps[i++ & 1023]));
	}
}

void model_make(benchmark::State& state, Model m)
{
	BridgeSpec s = w11(m);
	s.theta1 = s.theta2 = 0.4; // equal angles, which every version of the table holds
	int i = 0;
	for (auto _ : state) {
		s.volume = 13.6e-12 * (1 + 1e-3 * (i++ & 15)); // a new bridge each time, as in a packing
		benchmark::DoNotOptimize(make_bridge(s).rupture);
	}
}

void solver_force(benchmark::State& state)
{
	const BridgeSpec s = w11(Model::willett_full);
	const yl::Bridge b(s.R1, s.R2, s.volume, 0);
	int              i = 0;
	for (auto _ : state) {
		benchmark::DoNotOptimize(b.solve(b.rupture_gap() * ((i++ % 16) + 0.5) / 16, s.gamma).force_neck);
	}
}
} // namespace

int main(int argc, char** argv)
{
	for (const auto& row : models()) benchmark::RegisterBenchmark(row.name, model_force, row.model);
	benchmark::RegisterBenchmark("young_laplace", solver_force)->Unit(benchmark::kMicrosecond);
	for (Model m : { Model::willett_full, Model::young_laplace_table })
		benchmark::RegisterBenchmark((std::string(name_of(m)) + "/make").c_str(), model_make, m)->Unit(benchmark::kMicrosecond);
	benchmark::Initialize(&argc, argv);
	benchmark::RunSpecifiedBenchmarks();
	benchmark::Shutdown();
	return 0;
}
