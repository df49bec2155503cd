// The two-body critical time step: the stability limit of YADE's leapfrog for one spring-dashpot,
// applied to the normal and the tangential motion of a pair with the dashpots of its bridge.
#include "CriticalDt.hpp"

#include <limits>
#include <memory>

namespace yade {

Real pendular::oscillatorLimit(Real k, Real c, Real m)
{
	if (!(m > 0) || !math::isfinite(m)) return std::numeric_limits<Real>::infinity();
	if (!(k > 0)) return c > 0 ? 2 * m / c : std::numeric_limits<Real>::infinity(); // the limit k -> 0: a damper alone
	const Real w0 = math::sqrt(k / m), z = c / (2 * math::sqrt(k * m));
	return 2 / w0 * (math::sqrt(1 + z * z) - z);
}

Real pendular::tangentialMass(const Body& b1, const Body& b2)
{
	Real inverse = 0;
	for (const Body* b : { &b1, &b2 }) {
		if (heavy(*b)) continue;
		inverse += 1 / b->state->mass;
		const auto* sphere = dynamic_cast<const Sphere*>(b->shape.get());
		const Real  inertia = b->state->inertia.minCoeff();
		if (sphere && inertia > 0) inverse += sphere->radius * sphere->radius / inertia;
	}
	return inverse > 0 ? 1 / inverse : std::numeric_limits<Real>::infinity();
}

Real pendular::effectiveMass(const Body& b1, const Body& b2)
{
	const Real mass1 = b1.state->mass, mass2 = b2.state->mass;
	const bool heavy1 = heavy(b1), heavy2 = heavy(b2);
	if (heavy1 && !heavy2) return mass2;
	if (heavy2 && !heavy1) return mass1;
	return (mass1 > 0 && mass2 > 0) ? mass1 * mass2 / (mass1 + mass2) : math::max(mass1, mass2);
}

Real pendular::pairCriticalDt(const PendularPhys& p, const Body& b1, const Body& b2)
{
	if (heavy(b1) && heavy(b2)) return std::numeric_limits<Real>::infinity();
	Real cn = p.cn, cs = p.cs;
	std::shared_ptr<const capillary::ViscousBridge> viscous = p.viscous;
	if (!viscous && p.wet && p.film && p.eta > 0)
		viscous = p.viscousOf(p.VbMax);
	if (viscous) {
		double ct, cr;
		bool near;
		viscous->tangential_coefficients(0, ct, cr, near);
		cn += viscous->normal_coefficient(0);
		cs += ct + cr;
	}
	return math::min(oscillatorLimit(p.kn, cn, effectiveMass(b1, b2)), oscillatorLimit(p.ks, cs, tangentialMass(b1, b2)));
}

} // namespace yade
