// Round trip of a cache line between two threads [ns]: one thread writes a counter, the other answers
// by writing it back, 100 000 times; the median of 7 batches is printed. On this project's VM (two
// vCPUs of an AMD EPYC) it tells the machine's two modes apart: 55-110 ns (probably both vCPUs sharing
// a cache) and 300-420 ns (probably not: every line that one core wrote and the other reads then crosses
// between chips, and a two-thread step of the ci shear cell ran at 0.8-1.1x of one thread, 1.3-1.5x
// once the gathering streamed the bodies that the other thread reads). The
// benchmarks print it next to every timed run so that their ratios can be read with the mode they
// were measured in. Not a test.
// With --parallel, the machine's parallel speed instead: the time per record of one thread updating its
// own records alone, over that of each of two threads doing as much at once (1: two cores' worth; 0.5:
// each thread at half speed, as if the two vCPUs shared one core). On one two-vCPU VM, sampled every 1-2 s for 7
// minutes, it was 0.5 in 27 of 300 samples, at any round trip.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <random>
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

// Records of two cache lines, updated in a shuffled order (as a pass over interactions reads its
// records and bodies): read, compute, write, in the thread's own memory only.
struct alignas(64) Record {
	double value[16];
};
constexpr int parallelRecords = 2000, parallelRounds = 1500;

void update(std::vector<Record>& records, const std::vector<int>& order, int round)
{
	for (int i = 0; i < parallelRecords; ++i) {
		if (i + 8 < parallelRecords) __builtin_prefetch(&records[order[i + 8]]);
		Record&      r = records[order[i]];
		const double v = r.value[0] * 0.999 + r.value[3] * 1e-3 + std::sqrt(r.value[6] * r.value[6] + 1.0) * 1e-6 + round * 1e-9;
		for (int k = 0; k < 12; k += 3)
			r.value[k] = v;
	}
}

double median(std::vector<double> v)
{
	std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
	return v[v.size() / 2];
}

double parallelSpeed()
{
	using Clock = std::chrono::steady_clock;
	const auto          ns = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::nano>(b - a).count(); };
	std::vector<Record> mine(parallelRecords), theirs(parallelRecords);
	std::vector<int>    order(parallelRecords), otherOrder(parallelRecords);
	std::iota(order.begin(), order.end(), 0);
	std::iota(otherOrder.begin(), otherOrder.end(), 0);
	std::mt19937 shuffle(1);
	std::shuffle(order.begin(), order.end(), shuffle);
	std::shuffle(otherOrder.begin(), otherOrder.end(), shuffle);
	std::vector<double> alone, first, second;
	for (int round = 0; round < parallelRounds; ++round) {
		const auto start = Clock::now();
		update(mine, order, round);
		alone.push_back(ns(start, Clock::now()));
	}
	// Both threads, each its own records, started together at every round.
	std::atomic<int> go { 0 }, done { 0 };
	std::thread      other([&] {
		for (int round = 0; round < parallelRounds; ++round) {
			while (go.load(std::memory_order_acquire) != round + 1) { }
			const auto start = Clock::now();
			update(theirs, otherOrder, round);
			second.push_back(ns(start, Clock::now()));
			done.store(round + 1, std::memory_order_release);
		}
	});
	for (int round = 0; round < parallelRounds; ++round) {
		go.store(round + 1, std::memory_order_release);
		const auto start = Clock::now();
		update(mine, order, round);
		first.push_back(ns(start, Clock::now()));
		while (done.load(std::memory_order_acquire) != round + 1) { }
	}
	other.join();
	return median(alone) / std::max(median(first), median(second));
}
} // namespace

int main(int argc, char** argv)
{
	if (argc > 1 && std::strcmp(argv[1], "--parallel") == 0) {
		std::printf("%.2f\n", parallelSpeed());
		return 0;
	}
	std::vector<double> ns;
	for (int k = 0; k < 7; ++k)
		ns.push_back(batch(100000));
	std::printf("%.1f\n", median(ns));
	return 0;
}
