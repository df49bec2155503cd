// One generic test for the reference data of every model in the table: tests/data/models/<name>.csv
// (written by scripts/model_reference.py; each file records the command that made it). A model
// without its file fails here. Tolerance 1e-12 relative: the values are the kernels' own, so only
// rounding may differ (e.g. the quadrature of linear_irreversible's calibration, 2e-14).
#include "models.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace capillary;

class ReferenceData : public ::testing::TestWithParam<ModelInfo> { };

TEST_P(ReferenceData, KernelsReproduceTheFile)
{
	const ModelInfo&  m = GetParam();
	const std::string path = std::string(MODEL_REFERENCE_DIR) + "/" + m.name + ".csv";
	std::ifstream     in(path);
	ASSERT_TRUE(in) << "no reference data for model " << m.name << ": " << path << " (scripts/model_reference.py writes it)";
	std::string line;
	int         rows = 0;
	while (std::getline(in, line)) {
		if (line.empty() || line[0] == '#' || line[0] == 'R') continue; // comments and the header
		std::vector<double> v;
		std::stringstream   s(line);
		for (std::string cell; std::getline(s, cell, ',');) v.push_back(std::stod(cell));
		ASSERT_EQ(v.size(), 9u) << line;
		BridgeSpec spec;
		spec.model = m.model, spec.R1 = v[0], spec.R2 = v[1], spec.volume = v[2], spec.gamma = v[3], spec.theta1 = v[4], spec.theta2 = v[5];
		const Bridge b = make_bridge(spec);
		SCOPED_TRACE(line);
		EXPECT_NEAR(b.rupture, v[6], 1e-12 * v[6]);
		EXPECT_NEAR(bridge_force(b, v[7]), v[8], 1e-12 * v[8]);
		++rows;
	}
	EXPECT_GE(rows, 7 * 13) << "fewer rows than the Table 1 cases x 7 gaps";
}

INSTANTIATE_TEST_SUITE_P(EveryModel, ReferenceData, ::testing::ValuesIn(models()),
                         [](const ::testing::TestParamInfo<ModelInfo>& info) { return std::string(info.param.name); });
