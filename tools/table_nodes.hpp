// The node pool of the table generators (generate_young_laplace_table, generate_transfer_table): one
// row of text per (ln V*, theta, rho) node of young_laplace_table, computed on all cores.
#pragma once

#include "conventions.hpp"
#include "young_laplace_table.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace capillary {

// row(i, j, k) for every node (i in ln V*, j in theta, k in rho), in node order; progress on stderr.
// Returns an empty vector after printing every node that failed (a table is all or nothing).
inline std::vector<std::string> rows_over_nodes(const std::function<std::string(int, int, int)>& row)
{
	const int                n = yltable::n_lnv * yltable::n_theta * yltable::n_rho;
	const auto               node = [](int idx, int& i, int& j, int& k) {
                i = idx / (yltable::n_theta * yltable::n_rho), j = idx / yltable::n_rho % yltable::n_theta, k = idx % yltable::n_rho;
	};
	std::vector<std::string> rows(n), errors(n);
	std::atomic<int>         next { 0 }, done { 0 };
	auto                     work = [&] {
                for (int idx; (idx = next++) < n;) {
                        int i, j, k;
                        node(idx, i, j, k);
                        try {
                                rows[idx] = row(i, j, k);
                        } catch (const std::exception& e) {
                                errors[idx] = e.what();
                        }
                        if (++done % 200 == 0) std::fprintf(stderr, "%d of %d nodes\n", int(done), n);
                }
	};
	std::vector<std::thread> pool;
	for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t) pool.emplace_back(work);
	for (auto& t : pool) t.join();
	int failed = 0;
	for (int idx = 0; idx < n; ++idx)
		if (!errors[idx].empty()) {
			int i, j, k;
			node(idx, i, j, k);
			std::fprintf(stderr, "node V*=%.3g theta=%.1f deg rho=%.3f: %s\n", std::exp(yltable::lnv_node(i)), yltable::theta_node(j) * 180 / pi,
			             yltable::rho_nodes[k], errors[idx].c_str());
			++failed;
		}
	if (failed) {
		std::fprintf(stderr, "%d of %d nodes failed; no table written\n", failed, n);
		return {};
	}
	return rows;
}

} // namespace capillary
