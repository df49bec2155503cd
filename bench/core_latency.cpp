// Round trip of a cache line between two threads [ns]: one thread writes a counter, the other answers
// by writing it back, 100 000 times; the median of 7 batches is printed. On this project's VM (two
// vCPUs of an AMD EPYC) it tells the machine's two modes apart: 55-110 ns (probably both vCPUs sharing
// a cache) and 300-420 ns (probably not: every line that one core wrote and the other reads then crosses
// between chips, and a two-thread step of a shear cell ran at 0.8-1.1x of one thread). The
// benchmarks print it next to every timed run so that their ratios can be read with the mode they
// were measured in. Not a test.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>
#include <vector>

namespace {
alignas(64) std::atomic<long> line { 0 };

// One thread waits for the odd values and answers with the next even one.
void answer(long rounds)
{
	for (long i = 1; i < 2 * rounds; i += 2) {
		while (line.load(std::memory_order_acquire) != i) { }
		line.store(i + 1, std::memory_order_release);
	}
}

double batch(long rounds)
{
	line.store(0);
	std::thread other(answer, rounds);
	const auto start = std::chrono::steady_clock::now();
	for (long i = 0; i < 2 * rounds; i += 2) {
		while (line.load(std::memory_order_acquire) != i) { }
		line.store(i + 1, std::memory_order_release);
	}
	while (line.load(std::memory_order_acquire) != 2 * rounds) { }
	const auto end = std::chrono::steady_clock::now();
	other.join();
	return std::chrono::duration<double, std::nano>(end - start).count() / double(rounds);
}
} // namespace

int main()
{
	std::vector<double> ns;
	for (int k = 0; k < 7; ++k)
		ns.push_back(batch(100000));
	std::sort(ns.begin(), ns.end());
	std::printf("%.1f\n", ns[ns.size() / 2]);
	return 0;
}
