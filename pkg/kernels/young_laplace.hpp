// Exact pendular liquid bridge of fixed volume between two spheres (or a sphere and a plane),
// zero gravity: the axisymmetric meniscus of constant mean curvature (Young-Laplace equation),
// solved by multiple shooting from both contact lines to a matching plane (unknowns: the two
// filling angles and the pressure), with pseudo-arclength continuation along the branch of
// solutions. This is the reference the closed-form models were fitted to (Lian 1993,
// Willett 2000); no DEM code offers it at run time. SI units, radians.
//
// Profile in arc length s, rotating about the line of centres (x axis):
//   x' = cos(phi), y' = sin(phi), phi' = cos(phi)/y - P,   P = dp/gamma (dp = p_liquid - p_gas)
// The axial force F = pi gamma (2 y cos(phi) - P y^2) is a first integral of these equations: the
// neck method (at the narrowest section) and the contact-line method (at a contact line) give the
// same value, which checks the integration.
#pragma once

#include <array>
#include <vector>

namespace capillary {
namespace yl {

	struct Solution {
		double gap;           // [m] surface separation a
		double beta1, beta2;  // [rad] filling (half-embracing) angles on sphere 1 and 2 (beta2 = 0 for a plane)
		double contact_radius1, contact_radius2; // [m] radii of the contact lines
		double neck_radius;   // [m] smallest radius of the meniscus
		double pressure;      // [Pa] p_liquid - p_gas (negative: suction)
		double force_neck;    // [N] attraction by the neck (gorge) method
		double force_contact; // [N] attraction by the contact-line method (sphere 1)
		double volume;        // [m^3] volume of the computed profile (equals the input to ~1e-10)
		double volume1, volume2; // [m^3] the liquid on either side of the neck (the narrowest section), on
		                         // solid 1's and solid 2's side: where it goes when the bridge breaks there
	};

	// One bridge: the geometry is fixed, the gap varies. The constructor follows the branch of
	// solutions from contact (a = 0) by continuation and finds the largest gap with a stable bridge,
	// the true rupture distance: the fold of the branch or, for (nearly) equal spheres at larger
	// contact angles, the symmetry-breaking bifurcation before it.
	class Bridge {
	public:
		// R2 = infinity: sphere-plane. theta2 < 0: equal to theta1. Throws std::invalid_argument for
		// inputs outside R > 0, V > 0, theta in [0, pi/2), and std::runtime_error if no bridge exists.
		// tolerance: local error bound of the adaptive Dormand-Prince integration of the profile.
		Bridge(double R1, double R2, double volume, double theta1, double theta2 = -1, double tolerance = 1e-12);
		double   rupture_gap() const { return rupture_; }     // [m]
		// The stable bridge at gap in [0, rupture_gap()]; gamma [N/m] scales forces and pressure.
		// Throws std::invalid_argument outside that range.
		Solution solve(double gap, double gamma) const;

	private:
		struct Point {
			double beta1, s2, P, a; // filling angle on sphere 1, on sphere 2 (contact radius on a plane), pressure / gamma, gap; scaled by R1
		};
		// The bridge equations for a candidate: mismatch of the two arcs (height, angle) and relative
		// volume error against V (scaled by R1^3); false if the profile does not exist.
		bool residual(double beta1, double s2, double P, double a, double V, std::array<double, 3>& r) const;
		using Vec = std::array<double, 4>;
		Vec scaled(const Point& p) const; // (beta1 / beta0_, s2 / beta0_, P Pscale_, a / Lr_): arclength coordinates
		// The solution on the hyperplane through scaled(base) + step t normal to the unit tangent t:
		// pseudo-arclength corrector, regular at folds. Newton starts at the predictor, or at guess
		// if it differs from base.
		bool on_arc(const Point& base, const Vec& t, double step, const Point& guess, Point& out) const;
		// det of d(residual)/d(beta1, s2, P) at fixed gap (NaN where the bridge or its neighbours do not exist).
		double jacobian_det(const Point& p) const;
		double R1_, R2_, V_, t1_, t2_; // R2_, V_ dimensionless (/R1, /R1^3)
		double tol_;
		double L_;                     // length scale of the matching residual (scaled by R1)
		double beta0_ = 0, Lr_ = 0, Pscale_ = 0; // scales of the arclength: filling angle at contact, V^(1/3), a length
		double rupture_;               // [m]
		std::vector<Point> branch_;    // stable branch, from contact to rupture (a increasing)
	};

} // namespace yl
} // namespace capillary
