// Generates the young_laplace_table data from the Young-Laplace solver:
//   data/young_laplace_table.bin       float32 values of every node (young_laplace_table.hpp)
//   data/young_laplace_table_rows.csv  the rows: ln V*, rho, theta_s, the ridge of the rupture gap, the centre
//   tests/data/young_laplace_reference.csv  solver reference points
//
//   cmake --build build --target generate_young_laplace_table
//   build/generate_young_laplace_table data/young_laplace_table.bin data/young_laplace_table_rows.csv tests/data/young_laplace_reference.csv
//
// The axes are those of pkg/kernels/young_laplace_table.hpp. Lengths are scaled by the smaller
// radius (R_small = 1), gamma = 1. A row is one (ln V*, rho, theta_s) node: first its ridge, the
// theta_l where the rupture gap peaks (a scan of theta_l, or a bracket around the ridge of the row
// with the previous theta_s, then a golden-section search to 1e-7 rad), then at each theta_l node
// the rupture gap, the transfer share at rupture and the force at the tau nodes (neck method), as
// asinh(F / (2 pi Rh gamma force_delta)).
// Finished rows are appended to BIN.partial, so that an interrupted run resumes where it stopped.
// Runs on all cores, about 40 minutes on 2.
#include "conventions.hpp"
#include "young_laplace.hpp"
#include "young_laplace_table.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace capillary;

namespace {
const double inf = std::numeric_limits<double>::infinity();
const double deg = pi / 180;
const double tolerance = 1e-8;           // local error bound of the profile integration (1e-8 relative in gap and force)
const double scan_top = 88 * deg;        // the ridge is searched on [0, scan_top]
const double ridge_resolution = 1e-7;    // [rad]: an error e in the ridge leaves a cusp of 0.5 e^(2/3) (2e-5 at 1e-7)

struct Geometry {
	double R2, Rh, V;
};
Geometry geometry(int i, int k)
{
	const double rho = yltable::rho_nodes[k];
	const double R2 = rho == 0 ? inf : 1 / rho, Rh = rho == 0 ? 2.0 : harmonic_mean_radius(1, R2);
	return { R2, Rh, std::exp(yltable::lnv_node(i)) * Rh * Rh * Rh };
}

// Rupture gap at (theta_s, theta_l); -inf where the solver finds no bridge (the search treats it as low).
double rupture(const Geometry& g, double ts, double tl)
{
	try {
		return yl::Bridge(1.0, g.R2, g.V, ts, tl, tolerance).rupture_gap();
	} catch (const std::exception&) {
		return -inf;
	}
}

// The theta_l of the largest rupture gap on [lo, hi] by golden section (the gap is unimodal there).
double golden(const std::function<double(double)>& f, double lo, double hi)
{
	const double g = (std::sqrt(5.0) - 1) / 2;
	double       c = hi - g * (hi - lo), d = lo + g * (hi - lo), fc = f(c), fd = f(d);
	while (hi - lo > ridge_resolution) {
		if (fc > fd) hi = d, d = c, fd = fc, c = hi - g * (hi - lo), fc = f(c);
		else lo = c, c = d, fc = fd, d = lo + g * (hi - lo), fd = f(d);
	}
	return (lo + hi) / 2;
}

// The ridge of row (i, k) at theta_s = ts; guess < 0: none (scan).
double ridge(const Geometry& g, double ts, double guess)
{
	const auto f = [&](double tl) { return rupture(g, ts, tl); };
	if (guess >= 0) { // the ridge moves little between neighbouring theta_s: bracket it around the guess
		const double h = 2 * deg, lo = std::max(0.0, guess - h), hi = std::min(scan_top, guess + h);
		const double flo = f(lo), fmid = f(std::clamp(guess, lo, hi)), fhi = f(hi);
		if (fmid > flo && fmid > fhi) return golden(f, lo, hi);
	}
	const int           n = 45; // 2 deg steps
	std::vector<double> y(n);
	int                 best = 0;
	for (int m = 0; m < n; ++m) {
		y[m] = f(scan_top * m / (n - 1));
		if (y[m] > y[best]) best = m;
	}
	if (best == n - 1) return scan_top; // beyond the scan: the centre is capped anyway
	return golden(f, scan_top * std::max(0, best - 1) / (n - 1), scan_top * (best + 1) / (n - 1));
}

struct Row {
	double             ridge, center;
	std::vector<float> values; // n_tl x n_values
};

Row compute_row(int i, int k, int j, double guess)
{
	const Geometry g = geometry(i, k);
	const double   ts = yltable::theta_s_node(j);
	Row            r;
	r.ridge  = ridge(g, ts, guess);
	r.center = yltable::center_of(r.ridge);
	r.values.reserve(yltable::n_tl * yltable::n_values);
	for (int m = 0; m < yltable::n_tl; ++m) {
		const double     tl = yltable::theta_l_at(yltable::lobatto(m, yltable::n_tl), r.center);
		const yl::Bridge b(1.0, g.R2, g.V, ts, tl, tolerance);
		const double     ar = b.rupture_gap();
		if (!(ar > 0)) throw std::runtime_error("no positive rupture gap");
		const yl::Solution rup = b.solve(ar, 1.0);
		if (!(std::abs(rup.volume / g.V - 1) < 1e-6)) throw std::runtime_error("volume of the profile off by more than 1e-6");
		r.values.push_back(float(std::log(ar / g.Rh)));
		r.values.push_back(float(rup.volume1 / rup.volume));
		for (int n = 0; n < yltable::n_w; ++n) {
			const yl::Solution s = b.solve(yltable::gap_fraction(yltable::tau_node(n)) * ar, 1.0);
			// Against the force scale, not the force, which passes through 0 where the bridge turns repulsive.
			if (!(std::abs(s.force_neck - s.force_contact) < 1e-6 * 2 * pi * g.Rh)) throw std::runtime_error("neck and contact-line forces disagree");
			r.values.push_back(float(std::asinh(s.force_neck / (2 * pi * g.Rh * yltable::force_delta))));
		}
	}
	return r;
}

void write_reference(const char* path, const std::string& cmd)
{
	// Reference points: Gladkyy Table 1 cases and a sphere-plane bridge, gamma = 0.0206 N/m.
	struct Ref {
		const char* name;
		double      R1, R2, V, theta;
	};
	const Ref refs[] = { { "W11", 2.381e-3, 2.381e-3, 13.6e-12, 0 }, { "W24", 2.381e-3, 1.588e-3, 59.3e-12, 0 },
		                 { "W33", 2.381e-3, 1.191e-3, 127.8e-12, 0 }, { "R2", 19e-6, 32.5e-6, 12e-19, 10 * pi / 180 },
		                 { "plane", 1e-3, inf, 1e-11, 30 * pi / 180 } };
	std::ofstream r(path);
	r << "# Young-Laplace solver reference points, generated by: " << cmd << "\n"
	  << "case,R1_m,R2_m,volume_m3,theta_rad,gap_over_rupture,rupture_m,force_N_gamma_0.0206\n"
	  << std::setprecision(17);
	for (const Ref& ref : refs) {
		const yl::Bridge b(ref.R1, ref.R2, ref.V, ref.theta);
		for (double frac : { 0.0, 0.5, 0.95 })
			r << ref.name << "," << ref.R1 << "," << ref.R2 << "," << ref.V << "," << ref.theta << "," << frac << "," << b.rupture_gap() << ","
			  << b.solve(frac * b.rupture_gap(), 0.0206).force_neck << "\n";
	}
}
} // namespace

int main(int argc, char** argv)
{
	if (argc != 4) {
		std::fprintf(stderr, "usage: %s TABLE.bin ROWS.csv REFERENCE.csv\n", argv[0]);
		return 2;
	}
	std::string cmd = "generate_young_laplace_table";
	for (int a = 1; a < argc; ++a) cmd += std::string(" ") + argv[a];
	const auto start = std::chrono::steady_clock::now();

	// Resume: BIN.partial holds finished rows as (int32 row index, double ridge, double centre, values).
	const std::string  partial = std::string(argv[1]) + ".partial";
	std::vector<Row>   rows(yltable::n_rows);
	std::vector<char>  done(yltable::n_rows, 0);
	const size_t       n_floats = size_t(yltable::n_tl) * yltable::n_values;
	{
		std::ifstream in(partial, std::ios::binary);
		std::int32_t  idx;
		while (in.read(reinterpret_cast<char*>(&idx), sizeof idx)) {
			Row r;
			r.values.resize(n_floats);
			in.read(reinterpret_cast<char*>(&r.ridge), sizeof r.ridge);
			in.read(reinterpret_cast<char*>(&r.center), sizeof r.center);
			if (!in.read(reinterpret_cast<char*>(r.values.data()), std::streamsize(n_floats * sizeof(float))) || idx < 0 || idx >= yltable::n_rows) break;
			rows[idx] = std::move(r), done[idx] = 1;
		}
	}
	// A run killed while writing leaves a cut record: drop it before appending.
	{
		const size_t record = sizeof(std::int32_t) + 2 * sizeof(double) + n_floats * sizeof(float);
		size_t       rows_read = 0;
		for (char d : done) rows_read += d;
		if (std::filesystem::exists(partial)) std::filesystem::resize_file(partial, rows_read * record);
	}
	std::ofstream     out_partial(partial, std::ios::binary | std::ios::app);
	std::mutex        lock;
	std::atomic<int>  next { 0 }, finished { 0 }, failed { 0 };
	const int         n_columns = yltable::n_lnv * yltable::n_rho; // a task: all theta_s of one (ln V*, rho)
	auto              work = [&] {
                for (int col; (col = next++) < n_columns;) {
                        const int i = col / yltable::n_rho, k = col % yltable::n_rho;
                        double    guess = -1;
                        for (int j = 0; j < yltable::n_ts; ++j) {
                                const int idx = yltable::row_index(i, k, j);
                                // The ridge of the next theta_s, guessed as moving with theta_s.
                                const auto next_guess = [j](const Row& r) {
                                        return r.ridge < scan_top && j + 1 < yltable::n_ts ? r.ridge + yltable::theta_s_node(j + 1) - yltable::theta_s_node(j) : -1.0;
                                };
                                if (done[idx]) {
                                        guess = next_guess(rows[idx]);
                                        continue;
                                }
                                try {
                                        Row r = compute_row(i, k, j, guess);
                                        guess = next_guess(r);
                                        std::lock_guard<std::mutex> g(lock);
                                        const std::int32_t          id = idx;
                                        out_partial.write(reinterpret_cast<const char*>(&id), sizeof id);
                                        out_partial.write(reinterpret_cast<const char*>(&r.ridge), sizeof r.ridge);
                                        out_partial.write(reinterpret_cast<const char*>(&r.center), sizeof r.center);
                                        out_partial.write(reinterpret_cast<const char*>(r.values.data()), std::streamsize(n_floats * sizeof(float)));
                                        out_partial.flush();
                                        rows[idx] = std::move(r), done[idx] = 1;
                                } catch (const std::exception& e) {
                                        std::lock_guard<std::mutex> g(lock);
                                        std::fprintf(stderr, "row V*=%.3g rho=%.3f theta_s=%.2f deg: %s\n", std::exp(yltable::lnv_node(i)), yltable::rho_nodes[k],
                                                     yltable::theta_s_node(j) / deg, e.what());
                                        ++failed, guess = -1;
                                }
                                if (++finished % 20 == 0) {
                                        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                                        std::fprintf(stderr, "%d rows this run, %.0f s\n", int(finished), t);
                                }
                        }
                }
	};
	std::vector<std::thread> pool;
	for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t) pool.emplace_back(work);
	for (auto& t : pool) t.join();
	out_partial.close();
	if (failed) {
		std::fprintf(stderr, "%d rows failed; no table written (finished rows kept in %s)\n", int(failed), partial.c_str());
		return 1;
	}

	std::ofstream bin(argv[1], std::ios::binary);
	for (const Row& r : rows) bin.write(reinterpret_cast<const char*>(r.values.data()), std::streamsize(n_floats * sizeof(float)));
	std::ofstream csv(argv[2]);
	csv << "# young_laplace_table rows (data/young_laplace_table.bin holds their values), generated by: " << cmd << "\n"
	    << "# V* = V/Rh^3, Rh = 2 R1 R2/(R1 + R2) (2 R against a plane); rho = R_small/R_large, 0 = plane; theta_s on the smaller sphere\n"
	    << "# ridge_rad: the theta_l of the largest rupture gap (" << scan_top / deg << " deg: at or beyond the scan); center_rad: the centre of s = cbrt(theta_l - center)\n"
	    << "ln_vstar,rho,theta_s_rad,ridge_rad,center_rad\n"
	    << std::setprecision(17);
	for (int i = 0; i < yltable::n_lnv; ++i)
		for (int k = 0; k < yltable::n_rho; ++k)
			for (int j = 0; j < yltable::n_ts; ++j) {
				const Row& r = rows[yltable::row_index(i, k, j)];
				csv << yltable::lnv_node(i) << "," << yltable::rho_nodes[k] << "," << yltable::theta_s_node(j) << "," << r.ridge << "," << r.center << "\n";
			}
	write_reference(argv[3], cmd);
	std::remove(partial.c_str());
	const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
	std::printf("wrote %s, %s (%d rows) and %s in %.0f s\n", argv[1], argv[2], yltable::n_rows, argv[3], t);
	return 0;
}
