// Law2_ScGeom_PendularPhys_Bridge: YADE's dispatch into apply() (go), the film-mode requests that apply()
// makes, and the overlap check's rare path.
#include "Law2_ScGeom_PendularPhys_Bridge.hpp"
#include "CriticalDt.hpp"
#include "film.hpp"

#include <algorithm>

namespace yade {

YADE_PLUGIN((Law2_ScGeom_PendularPhys_Bridge));

namespace {
	// Forces of YADE's InteractionLoop: straight into the scene's force container.
	struct SceneSink {
		Scene*     scene;
		Body::id_t id1, id2;
		bool       enabled; // Interaction::isActive
		void       force(const Vector3r& f) const
		{
			if (!enabled) return;
			scene->forces.addForce(id1, -f);
			scene->forces.addForce(id2, f);
		}
		void forceTorque(const Vector3r& f, const Vector3r& t1, const Vector3r& t2) const
		{
			if (!enabled) return;
			force(f);
			scene->forces.addTorque(id1, t1);
			scene->forces.addTorque(id2, t2);
		}
	};

	using pendular::filmOf;
} // namespace

bool Law2_ScGeom_PendularPhys_Bridge::go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I)
{
	const auto      id1 = I->getId1(), id2 = I->getId2();
	const Body&     b1  = *Body::byId(id1, scene);
	const Body&     b2  = *Body::byId(id2, scene);
	const State&    de1 = *b1.state;
	const State&    de2 = *b2.state;
	const bool      periodic = scene->isPeriodic;
	const Vector3r  shift2   = periodic ? scene->cell->intrShiftPos(I->cellDist) : Vector3r::Zero();
	const Vector3r  shiftVel = periodic ? scene->cell->intrShiftVel(I->cellDist) : Vector3r::Zero();
	const PendularKinematics k { de1.pos, de1.vel, de1.angVel, de2.pos, de2.vel, de2.angVel, shift2, shiftVel,
		                     pendularOwner(scene->subdomain, b1.subdomain, b2.subdomain), id1, id2 };
	SceneSink       sink { scene, id1, id2, I->isActive };
	const ScGeom&   geom   = static_cast<const ScGeom&>(*ig);
	const auto      rotate = [&geom](Vector3r& v) { geom.rotate(v); };
	return apply(geom, static_cast<PendularPhys&>(*ip), k, scene->dt, rotate, sink);
}

bool Law2_ScGeom_PendularPhys_Bridge::filmsTouch(const PendularPhys& phys, const PendularKinematics& k, Real gap) const
{
	const FilmPair       ids    = filmPair(phys, k.id1, k.id2);
	const PendularState& sphere = filmOf(scene, ids.sphere);
	const PendularState& other  = filmOf(scene, ids.other);
	return gap <= sphere.thickness(phys.R1) + other.thickness(phys.R2);
}

void Law2_ScGeom_PendularPhys_Bridge::askFormation(PendularPhys& phys, const PendularKinematics& k)
{
	const FilmPair       ids    = filmPair(phys, k.id1, k.id2);
	const PendularState& sphere = filmOf(scene, ids.sphere);
	const PendularState& other  = filmOf(scene, ids.other);
	Real                 fromSphere, fromOther;
	if (phys.bonds) {
		// A new bond takes all the free liquid of both bodies (Richefeu2008 section 3.2, protocol 2),
		// shared among the bonds formed on a body in the same step (settleFilms).
		if (!phys.bondFormation) return;
		fromSphere = sphere.film;
		fromOther  = other.holds(phys.R2) ? other.film : 0;
	} else {
		// Shi & McCarthy (Elskamp2018 eq. 8; eq. 9-10 with a wall) from the films at the start of the step.
		fromSphere = capillary::film_contribution(phys.R1, phys.R2, sphere.film);
		fromOther  = math::isinf(phys.R2) ? capillary::wall_film_contribution(phys.R1, other.thickness(phys.R2))
		                                  : capillary::film_contribution(phys.R2, phys.R1, other.film);
	}
	// Too little liquid for a bridge (even before sharing the films): no request, the pair stays dry.
	if (!(fromSphere + fromOther >= phys.VbMin)) return;
	phys.pending = true;
	const std::lock_guard<std::mutex> lock(filmMutex);
	formations.push_back({ &phys, k.id1, k.id2, phys.swapped ? fromOther : fromSphere, phys.swapped ? fromSphere : fromOther, k.owned });
}

std::vector<Law2_ScGeom_PendularPhys_Bridge::FilmReturn> Law2_ScGeom_PendularPhys_Bridge::takeBondReturns()
{
	std::vector<FilmReturn> out;
	out.swap(bondReturns);
	std::sort(out.begin(), out.end(), [](const FilmReturn& a, const FilmReturn& b) { return std::make_pair(a.id, a.partner) < std::make_pair(b.id, b.partner); });
	return out;
}

Law2_ScGeom_PendularPhys_Bridge::OverlapReport Law2_ScGeom_PendularPhys_Bridge::takeOverlaps()
{
	const std::lock_guard<std::mutex> lock(overlapMutex);
	const OverlapReport               report = overlaps;
	overlaps                                 = OverlapReport {};
	return report;
}

void Law2_ScGeom_PendularPhys_Bridge::overlapSeen(Real depth, Body::id_t id1, Body::id_t id2, Real kn)
{
	const shared_ptr<Body>& b1 = Body::byId(id1, scene);
	const shared_ptr<Body>& b2 = Body::byId(id2, scene);
	if (pendular::heavy(*b1) && pendular::heavy(*b2)) return; // e.g. fixed spheres placed overlapping: no collision
	const Real radius = math::min(pendular::radiusOf(b1), pendular::radiusOf(b2));
	if (!(depth > overlapBound * radius)) return;
	// The normal speed at impact, from the energy of the undamped spring now: v0^2 = v^2 + kn d^2/m.
	const shared_ptr<Interaction> I      = scene->interactions->find(id1, id2);
	const bool                    shift  = scene->isPeriodic && I;
	const Vector3r                pos2   = b2->state->pos + (shift ? scene->cell->intrShiftPos(I->cellDist) : Vector3r::Zero());
	const Vector3r                vel2   = b2->state->vel + (shift ? scene->cell->intrShiftVel(I->cellDist) : Vector3r::Zero());
	const bool spheres = dynamic_cast<const Sphere*>(b1->shape.get()) && dynamic_cast<const Sphere*>(b2->shape.get());
	// Two spheres: along the centres; with a wall or facet: the relative speed (a bound on its normal part).
	const Real vn = spheres ? (pos2 - b1->state->pos).normalized().dot(b1->state->vel - vel2) : (b1->state->vel - vel2).norm();
	const Real speed = math::sqrt(vn * vn + kn * depth * depth / pendular::effectiveMass(*b1, *b2));
	const std::lock_guard<std::mutex> lock(overlapMutex);
	++overlaps.count;
	if (depth / radius > overlaps.largest) {
		overlaps.largest = depth / radius;
		overlaps.id1     = id1;
		overlaps.id2     = id2;
		overlaps.overlap = depth;
		overlaps.radius  = radius;
		overlaps.speed   = speed;
	}
}

} // namespace yade
