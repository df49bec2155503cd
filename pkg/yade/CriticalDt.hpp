// The two-body critical time step of YADE's leapfrog for a pair of PendularMat bodies, and the masses
// of a pair that it and the contact parameters use.
#pragma once

#include "PendularPhys.hpp"
#include "YadeHeaders.hpp"

namespace yade {
namespace pendular {
	// A body that does not move under forces (not dynamic, or no mass) is an infinitely heavy partner.
	inline bool heavy(const Body& b) { return !b.isDynamic() || !(b.state->mass > 0); }
	// Stability limit of YADE's leapfrog (NewtonIntegrator: v(t+dt/2) = v(t-dt/2) + dt F(t)/m,
	// x(t+dt) = x(t) + dt v(t+dt/2)) for m x'' + c x' + k x = 0 with the damping force taken from
	// v(t-dt/2), as the Law2 does. With h = w0 dt, w0^2 = k/m, d = c dt/m, the step matrix of
	// (x, v) has trace 2 - h^2 - d and determinant 1 - d; Jury's conditions |1 - d| < 1 and
	// 1 + trace + det > 0 give h^2 + 2d < 4, i.e. dt < (2/w0)(sqrt(1 + z^2) - z) with
	// z = c/(2 sqrt(k m)): 2/w0 undamped, smaller with damping. It is the central-difference limit
	// with damping of Belytschko, Liu & Moran (2000), Nonlinear Finite Elements for Continua and
	// Structures, chapter 6. A damper alone (k = 0) is the limit 2 m/c; inf for no stiffness and no damping, or an immovable mass.
	Real oscillatorLimit(Real k, Real c, Real m);
	// Mass of the tangential motion of the contact point: 1/m_t = sum over the dynamic bodies of
	// 1/m + r^2/I (sliding plus rolling; r the sphere radius, I the smallest principal inertia);
	// 2/7 m for a solid sphere against a wall.
	Real tangentialMass(const Body& b1, const Body& b2);
	// Effective mass of the normal motion: a body that does not move under forces acts as an
	// infinitely heavy partner (if neither moves, the contact parameters still need a mass).
	Real effectiveMass(const Body& b1, const Body& b2);
	// Two-body critical time step [s] of the pair of bodies b1, b2 with the physics p: the smaller of the
	// limits of its normal and tangential spring-dashpots (inf if neither body moves).
	// The viscous forces of a bridge (eta > 0) are dashpots in parallel with the contact's; their
	// coefficients are largest at contact (S_eff = S_min), which bounds the separated bridge too.
	// A film-mode pair has no bridge yet when its interaction is made (its volume is known only when
	// it forms): its limit is that of the largest bridge it can form, VbMax. That bounds every
	// volume: Pitois' coefficient grows with V (Elskamp2018 eq. 26), Adams-Perchard's and Goldman's
	// do not depend on it (eq. 25, 28, 29).
	Real pairCriticalDt(const PendularPhys& p, const Body& b1, const Body& b2);
} // namespace pendular
} // namespace yade
