// The exact transfer ratio at rupture, tabulated (see transfer.hpp and tools/generate_transfer_table.cpp).
#include "transfer.hpp"
#include "young_laplace_table.hpp"

#include <cmath>
#include <stdexcept>

namespace capillary {

namespace {
	constexpr int row_len = 4; // ln_vstar, theta, rho, transfer_small
	const double  table[] = {
#include "transfer_table_data.inc"
	};
	static_assert(sizeof(table) / sizeof(double) == size_t(yltable::n_lnv) * yltable::n_theta * yltable::n_rho * row_len,
	              "data/transfer_table.csv does not match the axes of young_laplace_table: regenerate it (tools/generate_transfer_table.cpp)");

	const double* row(int i, int j, int k) { return yltable::node_row(table, row_len, i, j, k); }
} // namespace

double exact_transfer(double R1, double R2, double volume, double theta1, double theta2)
{
	static const bool nodes_ok = (yltable::check_nodes(table, row_len, "data/transfer_table.csv"), true); // once
	(void)nodes_ok;
	check_radii(R1, R2);
	if (!(volume > 0 && std::isfinite(volume))) out_of_range("volume", volume, "(0, inf)", "m^3");
	const yltable::Stencil s = yltable::locate("exact transfer table", R1, R2, volume, theta1, theta2);
	double                 small = 0;
	yltable::for_each_node(s, [&small](double weight, int i, int j, int k) { small += weight * row(i, j, k)[3]; });
	small = std::fmin(1.0, std::fmax(0.0, small)); // a share; the interpolation stays well inside (0, 1)
	return s.small_first ? small : 1 - small;
}

} // namespace capillary
