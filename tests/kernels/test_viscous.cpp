// Viscous bridge forces and the dynamic rupture distance: each formula against a literal evaluation
// of the equation as printed in Elskamp & Kruggel-Emden 2018 (written here independently of
// viscous.cpp), the S_min floor, directions and signs, eta = 0, the wall limit, symmetry under
// swapping the particles, and refused input.
#include "viscous.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

using namespace capillary;

namespace {

const double inf = std::numeric_limits<double>::infinity();

// ---- literal transcriptions of Elskamp2018 (r_reff = r_i r_j / (r_i + r_j), after eq. 25) -----
double paperReff(double ri, double rj) { return ri * rj / (ri + rj); }
// S_min = 0.001 r_reff "is introduced and added to S" (after eq. 29).
double paperS(double S, double reff, double factor = 0.001) { return S + factor * reff; }
// eq. (25): |F| / v_n
double paperAdams(double eta, double reff, double S) { return 6 * pi * eta * std::pow(reff, 2) / S; }
// eq. (26), printed form
double paperPitois(double eta, double reff, double S, double V)
{
	return 6 * pi * eta * std::pow(reff, 2) / S * std::pow(1 - 1 / std::sqrt(1 + V / (pi * reff * std::pow(S, 2))), 2);
}
// eq. (28), (29): coefficients of v_r^t and of omega_r x n_ij
double paperGoldmanT(double eta, double reff, double S) { return 6 * pi * eta * reff * (8. / 15 * std::log(reff / S) + 0.9588); }
double paperGoldmanR28(double eta, double reff, double S) { return 6 * pi * eta * reff * (2. / 15 * std::log(reff / S) - 0.2526); }
double paperGoldmanR29(double eta, double reff, double S)
{
	return 6 * pi * eta * reff / 8 * std::pow(reff / (S + reff), 4) * (1 - 3 * reff / (8 * (S + reff)));
}
// eq. (33)
double paperDynamic(double Srup, double v, double eta, double sigma) { return Srup * (1 + std::sqrt(v * eta / sigma)); }

Vec3   cross3(const Vec3& a, const Vec3& b) { return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] }; }
double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3   neg(const Vec3& a) { return { -a[0], -a[1], -a[2] }; }

// Pitois' validation case (Elskamp2018 section 3.1): r1 = r2 = 4 mm, V = 5e-10 m^3, sigma = 21 mN/m,
// eta = 0.1 Pa s; and an unequal pair.
const double R = 4e-3, V = 5e-10, eta = 0.1, sigma = 21e-3;

void expectThrowsNaming(const std::function<void()>& f, const std::string& name)
{
	try {
		f();
		ADD_FAILURE() << "no exception, expected one naming " << name;
	} catch (const std::invalid_argument& e) {
		EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
		EXPECT_NE(std::string(e.what()).find("allowed range"), std::string::npos) << e.what();
	}
}

} // namespace

TEST(Viscous, ReducedRadiusIsHalfTheHarmonicMean)
{
	EXPECT_DOUBLE_EQ(reduced_radius(4e-3, 4e-3), 2e-3);
	EXPECT_DOUBLE_EQ(reduced_radius(2e-3, 6e-3), paperReff(2e-3, 6e-3));
	EXPECT_DOUBLE_EQ(reduced_radius(2e-3, 6e-3), harmonic_mean_radius(2e-3, 6e-3) / 2);
	EXPECT_DOUBLE_EQ(reduced_radius(2e-3, wall_radius), 2e-3);
}

TEST(Viscous, SeparationFloorIsAddedNotClamped)
{
	const double rs = paperReff(R, 3e-3);
	EXPECT_DOUBLE_EQ(effective_separation(1e-4, R, 3e-3), paperS(1e-4, rs)); // added, also far above S_min
	EXPECT_DOUBLE_EQ(effective_separation(0, R, 3e-3), 0.001 * rs);
	EXPECT_DOUBLE_EQ(effective_separation(-1e-4, R, 3e-3), 0.001 * rs); // overlap: as at contact
	EXPECT_DOUBLE_EQ(effective_separation(1e-4, R, 3e-3, 0.01), paperS(1e-4, rs, 0.01));
}

TEST(Viscous, NormalAgainstPrintedEquations)
{
	for (double R2 : { R, 3e-3, 1e-3 })
		for (double S : { 0.0, 1e-7, 1e-5, 1e-4, 1e-3 }) {
			const double rs = paperReff(R, R2), Se = paperS(S, rs);
			EXPECT_NEAR(normal_viscous_coefficient(NormalViscous::adams_perchard, S, R, R2, eta, 0), paperAdams(eta, rs, Se),
			            1e-13 * paperAdams(eta, rs, Se));
			EXPECT_NEAR(normal_viscous_coefficient(NormalViscous::pitois, S, R, R2, eta, V), paperPitois(eta, rs, Se, V),
			            1e-10 * paperPitois(eta, rs, Se, V))
			        << "R2 " << R2 << " S " << S;
			// signed force on particle 1 along n: -c v_n
			EXPECT_NEAR(normal_viscous_force(NormalViscous::pitois, S, 2e-3, R, R2, eta, V), -paperPitois(eta, rs, Se, V) * 2e-3,
			            1e-10 * paperPitois(eta, rs, Se, V) * 2e-3);
		}
	// Pitois -> Adams & Perchard for a large bridge: x = V / (pi r* S_eff^2) = 1.2e6 here, ratio
	// (1 - 1/sqrt(1 + x))^2 = 1 - 2/sqrt(x) + O(1/x) = 0.9981
	const double x = 0.5 * R * R * R / (pi * R / 2 * std::pow(1e-7 + 0.001 * R / 2, 2));
	EXPECT_NEAR(normal_viscous_coefficient(NormalViscous::pitois, 1e-7, R, R, eta, 0.5 * R * R * R) /
	                    normal_viscous_coefficient(NormalViscous::adams_perchard, 1e-7, R, R, eta, 0),
	            1 - 2 / std::sqrt(x), 2 / x);
}

TEST(Viscous, NormalNamesAndDefault)
{
	EXPECT_EQ(normal_viscous_from_name("pitois"), NormalViscous::pitois);
	EXPECT_EQ(normal_viscous_from_name("adams_perchard"), NormalViscous::adams_perchard);
	EXPECT_STREQ(name_of(NormalViscous::pitois), "pitois");
	EXPECT_EQ(normal_viscous_laws().front().law, NormalViscous::pitois); // the default first
	try {
		normal_viscous_from_name("stokes");
		ADD_FAILURE();
	} catch (const std::invalid_argument& e) {
		EXPECT_NE(std::string(e.what()).find("pitois, adams_perchard"), std::string::npos) << e.what();
	}
}

TEST(Viscous, TangentialAgainstPrintedEquations)
{
	for (double R2 : { R, 3e-3 })
		for (double S : { 0.0, 1e-6, 1e-5, 1e-4, 1.5e-4, 5e-4, 1e-3, 3e-3 }) {
			const double rs = paperReff(R, R2), Se = paperS(S, rs);
			double       ct, cr;
			bool         near;
			tangential_viscous_coefficients(S, R, R2, eta, 0.001, ct, cr, near);
			EXPECT_EQ(near, Se < 0.1 * rs);
			EXPECT_NEAR(ct, paperGoldmanT(eta, rs, Se), 1e-12 * paperGoldmanT(eta, rs, Se));
			const double crp = Se < 0.1 * rs ? paperGoldmanR28(eta, rs, Se) : paperGoldmanR29(eta, rs, Se);
			EXPECT_NEAR(cr, crp, 1e-12 * crp) << "S " << S;
			EXPECT_GT(cr, 0);
			// the vectors: F1 = -ct v_t - cr (omega_r x n), M1 = R1 n x F1, M2 = R2 n x F1
			const Vec3 n { 0.6, 0, 0.8 }, v { 0.01, -0.02, 0.03 }, w1 { 1, 2, -3 }, w2 { -2, 0.5, 1 };
			const TangentialViscous t = tangential_viscous(S, n, v, w1, w2, R, R2, eta);
			const double            vn = dot3(v, n);
			Vec3                    wr, expect;
			for (int k = 0; k < 3; ++k) wr[k] = R * w1[k] + R2 * w2[k];
			const Vec3 wxn = cross3(wr, n);
			for (int k = 0; k < 3; ++k) expect[k] = -ct * (v[k] - vn * n[k]) - crp * wxn[k];
			const Vec3 nxF = cross3(n, expect);
			for (int k = 0; k < 3; ++k) {
				EXPECT_NEAR(t.force[k], expect[k], 1e-12 * std::sqrt(dot3(expect, expect)));
				EXPECT_NEAR(t.moment1[k], R * nxF[k], 1e-12 * R * std::sqrt(dot3(expect, expect)));
				EXPECT_NEAR(t.moment2[k], R2 * nxF[k], 1e-12 * R2 * std::sqrt(dot3(expect, expect)));
			}
			EXPECT_NEAR(dot3(t.force, n), 0, 1e-12 * std::sqrt(dot3(expect, expect))); // tangential
		}
}

// The two Goldman branches at S_eff = 0.1 r*: c_t continuous, c_r jumps by 3.3 % (documented).
TEST(Viscous, GoldmanBranchJump)
{
	const double rs = R / 2, Sb = 0.1 * rs - 0.001 * rs; // S_eff = 0.1 r* exactly at S = Sb
	double       ct_lo, cr_lo, ct_hi, cr_hi;
	bool         near_lo, near_hi;
	tangential_viscous_coefficients(Sb * (1 - 1e-9), R, R, eta, 0.001, ct_lo, cr_lo, near_lo);
	tangential_viscous_coefficients(Sb * (1 + 1e-9), R, R, eta, 0.001, ct_hi, cr_hi, near_hi);
	EXPECT_TRUE(near_lo);
	EXPECT_FALSE(near_hi);
	EXPECT_NEAR(ct_hi / ct_lo, 1, 1e-6);
	const double jump = (cr_hi - cr_lo) / cr_hi;
	EXPECT_NEAR(jump, 0.0330, 0.0005); // 0.05627 (29) vs 0.05441 (28), in units of 6 pi eta r*
	EXPECT_NEAR(cr_lo / (6 * pi * eta * rs), 0.05441, 1e-5);
	EXPECT_NEAR(cr_hi / (6 * pi * eta * rs), 0.05627, 1e-5);
}

TEST(Viscous, TranslationalCoefficientFlooredAtZeroFarAway)
{
	const double rs = R / 2;
	double       ct, cr;
	bool         near;
	tangential_viscous_coefficients(5 * rs, R, R, eta, 0.001, ct, cr, near); // S_eff < 6.03 r*: printed form
	EXPECT_NEAR(ct, paperGoldmanT(eta, rs, paperS(5 * rs, rs)), 1e-12 * ct);
	tangential_viscous_coefficients(7 * rs, R, R, eta, 0.001, ct, cr, near); // printed form < 0
	EXPECT_LT(paperGoldmanT(eta, rs, paperS(7 * rs, rs)), 0);
	EXPECT_EQ(ct, 0);
	EXPECT_GT(cr, 0);
}

// Each force opposes the motion it damps: F . v <= 0 (dissipation >= 0) on random velocities.
TEST(Viscous, ForcesOpposeRelativeMotion)
{
	std::mt19937                           gen(42);
	std::uniform_real_distribution<double> u(-1, 1), s(-1e-4, 3e-3);
	for (int i = 0; i < 2000; ++i) {
		Vec3 n { u(gen), u(gen), u(gen) };
		const double nn = std::sqrt(dot3(n, n));
		if (nn < 1e-3) continue;
		for (auto& x : n) x /= nn;
		const Vec3   v { u(gen), u(gen), u(gen) }, w1 { 100 * u(gen), 100 * u(gen), 100 * u(gen) }, w2 { 100 * u(gen), 100 * u(gen), 100 * u(gen) };
		const double S = s(gen), R2 = i % 3 == 0 ? wall_radius : 1e-3 + 4e-3 * (u(gen) + 1);
		const double vn = dot3(v, n);
		for (auto law : { NormalViscous::pitois, NormalViscous::adams_perchard }) {
			const double f = normal_viscous_force(law, S, vn, R, R2, eta, V);
			EXPECT_LE(f * vn, 0); // power of F1 = f n in the relative motion v1 - v2
			EXPECT_TRUE(std::isfinite(f));
		}
		// translation alone and rotation alone: power of (F1, -F1, M1, M2) <= 0
		const Vec3              zero { 0, 0, 0 };
		const TangentialViscous tt = tangential_viscous(S, n, v, zero, zero, R, R2, eta);
		EXPECT_LE(dot3(tt.force, v), 0);
		const Vec3              w2r = is_wall(R2) ? zero : w2;
		const TangentialViscous tr  = tangential_viscous(S, n, zero, w1, w2r, R, R2, eta);
		const double            Pr  = dot3(tr.moment1, w1) + dot3(tr.moment2, w2r);
		EXPECT_LE(Pr, 1e-14 * std::sqrt(dot3(tr.force, tr.force)));
		// rotational power = F1 . (omega_r x n): the moments turn omega_r x n into a surface velocity
		Vec3 wr;
		for (int k = 0; k < 3; ++k) wr[k] = R * w1[k] + (is_wall(R2) ? 0 : R2 * w2r[k]);
		EXPECT_NEAR(Pr, dot3(tr.force, cross3(wr, n)), 1e-9 * std::abs(Pr) + 1e-18);
	}
}

// Documented property of the paper's form: c_t != c_r, so translation and rotation together can
// produce positive power (v_t = -k (omega_r x n) with k between c_r/c_t and 1).
TEST(Viscous, CombinedTangentialPowerNotSignDefinite)
{
	const Vec3 n { 0, 0, 1 }, w1 { 0, 10, 0 }, zero { 0, 0, 0 };
	const double S = 1e-5;
	double       ct, cr;
	bool         near;
	tangential_viscous_coefficients(S, R, R, eta, 0.001, ct, cr, near);
	ASSERT_GT(ct, cr);
	const Vec3   w = cross3({ R * w1[0], R * w1[1], R * w1[2] }, n);
	const double k = (cr / ct + 1) / 2;
	const Vec3   v { -k * w[0], -k * w[1], -k * w[2] };
	const TangentialViscous t = tangential_viscous(S, n, v, w1, zero, R, R, eta);
	const double            P = dot3(t.force, v) + dot3(t.moment1, w1);
	EXPECT_GT(P, 0);
}

TEST(Viscous, EtaZeroGivesExactlyZero)
{
	for (double S : { -1e-4, 0.0, 1e-5, 1e-3 }) {
		EXPECT_EQ(normal_viscous_force(NormalViscous::pitois, S, 3.0, R, R, 0, V), 0);
		EXPECT_EQ(normal_viscous_force(NormalViscous::adams_perchard, S, -3.0, R, wall_radius, 0, 0), 0);
		const TangentialViscous t = tangential_viscous(S, { 1, 0, 0 }, { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 }, R, R, 0);
		for (int k = 0; k < 3; ++k) {
			EXPECT_EQ(t.force[k], 0);
			EXPECT_EQ(t.moment1[k], 0);
			EXPECT_EQ(t.moment2[k], 0);
		}
	}
	EXPECT_EQ(dynamic_rupture_distance(1e-3, 5, 0, sigma), 1e-3);
}

TEST(Viscous, WallIsTheLimitOfALargeSphere)
{
	const double big = 1e3; // Plausible::radius_max, r* = R1 (1 - 4e-6)
	for (double S : { 0.0, 1e-5, 1e-4, 1e-3 }) {
		for (auto law : { NormalViscous::pitois, NormalViscous::adams_perchard }) {
			const double fw = normal_viscous_force(law, S, 0.01, R, wall_radius, eta, V);
			const double fb = normal_viscous_force(law, S, 0.01, R, big, eta, V);
			EXPECT_TRUE(std::isfinite(fw));
			EXPECT_NEAR(fw / fb, 1, 1e-5);
		}
		const Vec3              n { 0, 1, 0 }, v { 0.1, 0.2, -0.1 }, w1 { 3, -1, 2 }, zero { 0, 0, 0 };
		const TangentialViscous tw = tangential_viscous(S, n, v, w1, zero, R, wall_radius, eta);
		const TangentialViscous tb = tangential_viscous(S, n, v, w1, zero, R, big, eta);
		for (int k = 0; k < 3; ++k) {
			EXPECT_TRUE(std::isfinite(tw.force[k]) && std::isfinite(tw.moment1[k]));
			EXPECT_NEAR(tw.force[k], tb.force[k], 1e-5 * std::sqrt(dot3(tb.force, tb.force)));
			EXPECT_NEAR(tw.moment1[k], tb.moment1[k], 1e-5 * R * std::sqrt(dot3(tb.force, tb.force)));
			EXPECT_EQ(tw.moment2[k], 0);
		}
	}
}

// Swapping the particles: n -> -n, v_rel -> -v_rel, (R1, omega1) <-> (R2, omega2): the force on the
// new particle 1 is minus the old one, the moments swap.
TEST(Viscous, SymmetricUnderSwappingParticles)
{
	const double R2 = 2.5e-3;
	const Vec3   n { 0.48, 0.6, 0.64 }, v { 0.01, -0.03, 0.02 }, w1 { 5, -2, 1 }, w2 { -1, 4, 3 };
	for (double S : { 0.0, 1e-5, 2e-4, 1e-3 }) {
		for (auto law : { NormalViscous::pitois, NormalViscous::adams_perchard }) {
			const double vn = dot3(v, n);
			// v_n = (v1 - v2) . n is unchanged by the swap; the force along the new n is the same
			EXPECT_DOUBLE_EQ(normal_viscous_force(law, S, vn, R, R2, eta, V), normal_viscous_force(law, S, vn, R2, R, eta, V));
		}
		const TangentialViscous a = tangential_viscous(S, n, v, w1, w2, R, R2, eta);
		const TangentialViscous b = tangential_viscous(S, neg(n), neg(v), w2, w1, R2, R, eta);
		const double            F = std::sqrt(dot3(a.force, a.force));
		for (int k = 0; k < 3; ++k) {
			EXPECT_NEAR(b.force[k], -a.force[k], 1e-12 * F);
			EXPECT_NEAR(b.moment1[k], a.moment2[k], 1e-12 * F * R);
			EXPECT_NEAR(b.moment2[k], a.moment1[k], 1e-12 * F * R);
		}
	}
}

TEST(Viscous, DynamicRuptureAgainstEq33)
{
	for (double Srup : { 1e-4, 1.3e-3 })
		for (double v : { 0.0, 1e-4, 1e-2, 1.0 }) {
			EXPECT_NEAR(dynamic_rupture_distance(Srup, v, eta, sigma), paperDynamic(Srup, v, eta, sigma), 1e-14 * Srup);
			EXPECT_DOUBLE_EQ(dynamic_rupture_distance(Srup, -v, eta, sigma), dynamic_rupture_distance(Srup, v, eta, sigma)); // |v1 - v2|
		}
	// Pitois' experiment (Elskamp2018 Fig. 5b): v = 10 mm/s, Ca = 0.048, S_rup,dyn = 1.218 S_rup
	EXPECT_NEAR(dynamic_rupture_distance(1, 10e-3, eta, sigma), 1 + std::sqrt(1e-3 / 21e-3), 1e-15);
}

TEST(Viscous, BadInputNamesTheParameter)
{
	const auto P = NormalViscous::pitois;
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, R, -1, V); }, "eta");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, R, NAN, V); }, "eta");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, R, inf, V); }, "eta");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, 0, R, eta, V); }, "R1");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, -R, eta, V); }, "R2");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, inf, R, eta, V); }, "R1");
	expectThrowsNaming([&] { normal_viscous_force(P, NAN, 0.1, R, R, eta, V); }, "S");
	expectThrowsNaming([&] { normal_viscous_force(P, inf, 0.1, R, R, eta, V); }, "S");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, NAN, R, R, eta, V); }, "v_n");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 1e300, R, R, eta, V); }, "v_n");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, R, eta, 0); }, "V* = V/R^3");
	expectThrowsNaming([&] { normal_viscous_force(NormalViscous::adams_perchard, 1e-5, 0.1, R, R, eta, -1); }, "volume");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, R, eta, V, 0); }, "S_min_factor");
	expectThrowsNaming([&] { normal_viscous_force(P, 1e-5, 0.1, R, R, eta, V, -1e-3); }, "S_min_factor");
	const Vec3 n { 1, 0, 0 }, z { 0, 0, 0 };
	expectThrowsNaming([&] { tangential_viscous(1e-5, { 1, 1, 0 }, z, z, z, R, R, eta); }, "|n|");
	expectThrowsNaming([&] { tangential_viscous(1e-5, n, { 0, NAN, 0 }, z, z, R, R, eta); }, "v_rel[1]");
	expectThrowsNaming([&] { tangential_viscous(1e-5, n, z, { inf, 0, 0 }, z, R, R, eta); }, "omega1[0]");
	expectThrowsNaming([&] { tangential_viscous(1e-5, n, z, z, { 0, 0, NAN }, R, R, eta); }, "omega2[2]");
	expectThrowsNaming([&] { tangential_viscous(1e-5, n, z, z, { 0, 1, 0 }, R, wall_radius, eta); }, "|omega2|");
	expectThrowsNaming([&] { tangential_viscous(1e-5, n, z, z, z, R, R, -eta); }, "eta");
	expectThrowsNaming([&] { dynamic_rupture_distance(0, 0.1, eta, sigma); }, "static_rupture");
	expectThrowsNaming([&] { dynamic_rupture_distance(inf, 0.1, eta, sigma); }, "static_rupture");
	expectThrowsNaming([&] { dynamic_rupture_distance(1e-3, NAN, eta, sigma); }, "v_rel");
	expectThrowsNaming([&] { dynamic_rupture_distance(1e-3, 0.1, -1, sigma); }, "eta");
	expectThrowsNaming([&] { dynamic_rupture_distance(1e-3, 0.1, eta, 0); }, "gamma");
}

// No NaN or inf for finite input within the limits, including S = 0, overlaps and the extremes.
TEST(Viscous, FiniteForExtremeInput)
{
	for (double S : { -1e3, -1e-9, 0.0, 1e-300, 1e-9, 1e3, 1e300 })
		for (double Rr : { 1e-9, 1e3 })
			for (double R2 : { 1e-9, 1e3, wall_radius })
				for (double f : { 1e-12, 1.0 }) {
					const double c = normal_viscous_force(NormalViscous::adams_perchard, S, 1e10, Rr, R2, 1e9, 0, f);
					EXPECT_TRUE(std::isfinite(c));
					const TangentialViscous t =
					        tangential_viscous(S, { 0, 0, 1 }, { 1e10, -1e10, 1e10 }, { 1e10, 1e10, -1e10 }, { 0, 0, 0 }, Rr, R2, 1e9, f);
					for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(t.force[k]) && std::isfinite(t.moment1[k]) && std::isfinite(t.moment2[k]));
				}
	EXPECT_TRUE(std::isfinite(normal_viscous_force(NormalViscous::pitois, 1e300, 1e10, R, R, 1e9, V)));
	EXPECT_TRUE(std::isfinite(dynamic_rupture_distance(1e4, 1e10, 1e9, 1e-7)));
}
