// Law2_ScGeom_PendularPhys_Bridge's liquid accounts outside the contact: the film-mode bridges formed
// and the liquid of broken ones moved to the films at the end of a step (settleFilms), the liquid
// of bridges and bodies removed from Python, bridges restored from a saved state, and the totals.
#include "Law2_ScGeom_PendularPhys_Bridge.hpp"
#include "PendularLoop.hpp"
#include "transfer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

namespace yade {

namespace {
	using pendular::filmOf;

	void refuseWhileRunning(const char* what)
	{
		if (Omega::instance().isRunning())
			throw std::runtime_error(std::string(what) + " while the simulation runs (O.run()): the bridges and films change under it; call O.pause() or O.wait() first");
	}
} // namespace

void Law2_ScGeom_PendularPhys_Bridge::settleFilms(Scene* current)
{
	if (formations.empty() && returns.empty()) return;
	// In the order of the pairs, whatever the order of the threads: a run is reproducible.
	std::sort(formations.begin(), formations.end(), [](const FilmFormation& a, const FilmFormation& b) {
		return std::make_pair(a.id1, a.id2) < std::make_pair(b.id1, b.id2);
	});
	// A film asked for more than it holds is shared in proportion to the requests (Elskamp2018
	// section 2.2.1: all the bridges of one step form under the same conditions).
	std::unordered_map<Body::id_t, Real> share; // per body: the sum of the requests, then the share granted
	for (const auto& f : formations) {
		share[f.id1] += f.take1;
		share[f.id2] += f.take2;
	}
	for (auto& s : share) {
		const Real demand = s.second, film = current->bodies->exists(s.first) ? filmOf(current, s.first).film : 0;
		s.second = demand > film ? film / demand : 1;
	}
	std::string error;
	for (const auto& f : formations) {
		// An engine between the loop and PendularCheck may have removed the pair or a body: nothing
		// was taken from the films yet, so the request is simply dropped.
		if (!current->bodies->exists(f.id1) || !current->bodies->exists(f.id2)) continue;
		const shared_ptr<Interaction>& I = current->interactions->find(f.id1, f.id2);
		if (!I || I->phys.get() != f.phys || !f.phys->pending) continue;
		PendularPhys&  phys = *f.phys;
		PendularState& s1   = filmOf(current, f.id1);
		PendularState& s2   = filmOf(current, f.id2);
		phys.pending        = false;
		Real v1 = f.take1 * share[f.id1], v2 = f.take2 * share[f.id2];
		if (v1 + v2 > phys.VbMax) { // capped: the rest stays on the films
			const Real scale = phys.VbMax / (v1 + v2);
			v1 *= scale;
			v2 *= scale;
		}
		v1 = math::min(v1, s1.film); // the shares hold to rounding: never more than the film
		v2 = math::min(v2, s2.film);
		if (!(v1 + v2 >= phys.VbMin)) continue;
		phys.Vb = v1 + v2;
		try {
			phys.buildBridge();
			phys.transfer1 = capillary::transfer_ratio(
			        capillary::Transfer(phys.transferIndex), phys.R1, phys.R2, phys.Vb, phys.bridge.rupture, phys.theta1, phys.theta2);
		} catch (const std::exception& e) {
			phys.Vb = 0;
			if (error.empty()) error = std::string(e.what()) + " (bridge " + std::to_string(f.id1) + "-" + std::to_string(f.id2) + " not formed)";
			continue;
		}
		s1.film -= v1;
		s2.film -= v2;
		phys.active = true;
		if (f.owned) {
			nBridges += 1;
			liquidVolume += phys.Vb;
			liquidFormed += phys.Vb;
		}
	}
	formations.clear();
	for (const auto& r : returns)
		giveBack(current, r.id, r.volume);
	returns.clear();
	if (!error.empty()) throw std::invalid_argument(error);
}

void Law2_ScGeom_PendularPhys_Bridge::releasePair(Scene* current, Interaction& I)
{
	auto* phys = dynamic_cast<PendularPhys*>(I.phys.get());
	if (!phys || !phys->active) return;
	refuseWhileRunning("removing a bridge");
	const Body::id_t id1 = I.getId1(), id2 = I.getId2();
	const bool       both = current->bodies->exists(id1) && current->bodies->exists(id2);
	if (!both || pendularOwner(current->subdomain, Body::byId(id1, current)->subdomain, Body::byId(id2, current)->subdomain)) {
		nBridges -= 1;
		liquidVolume -= phys->Vb;
		liquidReleased += phys->Vb;
		zeroEmptyTotals();
	}
	phys->active = false; // the interaction goes (or becomes potential) without the law
	if (!phys->film) return;
	// As a rupture; a share of a body that no longer exists leaves the scene.
	const FilmPair ids        = filmPair(*phys, id1, id2);
	const bool     otherHolds = !current->bodies->exists(ids.other) || filmOf(current, ids.other).holds(phys->R2);
	const Real     toSphere   = sphereShare(*phys, otherHolds);
	giveBack(current, ids.sphere, toSphere);
	giveBack(current, ids.other, phys->Vb - toSphere);
	phys->Vb = 0;
}

void Law2_ScGeom_PendularPhys_Bridge::giveBack(Scene* current, Body::id_t id, Real volume)
{
	if (current->bodies->exists(id)) filmOf(current, id).film += volume;
	else liquidRemoved += volume;
}

void Law2_ScGeom_PendularPhys_Bridge::zeroEmptyTotals()
{
	if (nBridges.get() == 0) liquidVolume.reset();
}

void Law2_ScGeom_PendularPhys_Bridge::eraseBody(Scene* current, Body::id_t id, bool clumpMembers)
{
	if (!current->bodies->exists(id)) return;
	const shared_ptr<Body> body = (*current->bodies)[id];
	if (clumpMembers && body->isClump()) // its members point at it (Clump::members is not exported by YADE's library)
		for (const auto& b : *current->bodies)
			if (b && b->isClumpMember() && b->clumpId == id) eraseBody(current, b->id, false);
	// Its bridges break as at rupture (the partners keep their shares); then its film, with its own
	// shares, leaves the scene.
	for (const auto& entry : body->intrs) releasePair(current, *entry.second);
	if (auto* state = dynamic_cast<PendularState*>(body->state.get())) {
		if (state->film > 0) refuseWhileRunning("O.bodies.erase of a body with a film");
		liquidRemoved += state->film;
	}
}

void Law2_ScGeom_PendularPhys_Bridge::clearBodies(Scene* current)
{
	for (const auto& I : *current->interactions) releasePair(current, *I);
	for (const auto& b : *current->bodies)
		if (b)
			if (auto* state = dynamic_cast<PendularState*>(b->state.get())) liquidRemoved += state->film;
}

void Law2_ScGeom_PendularPhys_Bridge::formBridge(Body::id_t id1, Body::id_t id2, Real pastRupture)
{
	refuseWhileRunning("formBridge()");
	const auto&       current = Omega::instance().getScene();
	const std::string pair    = "formBridge(id1=" + std::to_string(id1) + ", id2=" + std::to_string(id2) + "): ";
	if (!(pastRupture >= 0 && math::isfinite(pastRupture)))
		throw std::invalid_argument(pair + "pastRupture = " + capillary::format_value(pastRupture) + " m; allowed: a finite value >= 0 m");
	PendularLoop::syncScene(current.get(), true); // the loop reads the changed objects at its next step
	const shared_ptr<Interaction> I = current->interactions->find(id1, id2);
	if (!I || !I->isReal()) throw std::invalid_argument(pair + "no real interaction between these bodies (utils.createInteraction makes one)");
	auto* phys = dynamic_cast<PendularPhys*>(I->phys.get());
	auto* geom = dynamic_cast<const ScGeom*>(I->geom.get());
	if (!phys || !geom) throw std::invalid_argument(pair + "the interaction has no ScGeom and PendularPhys");
	if (!phys->wet || phys->modelIndex < 0) throw std::invalid_argument(pair + "the materials are dry (PendularMat.wet = False) or the bridge's liquid was rejected");
	if (phys->film) throw std::invalid_argument(pair + "liquid='film': a film-mode bridge takes its liquid from the films, not from a saved state");
	if (phys->active) throw std::invalid_argument(pair + "the interaction already has a bridge");
	const Real gap = -geom->penetrationDepth;
	if (!(gap <= phys->bridge.rupture + pastRupture))
		throw std::invalid_argument(pair + "gap = " + capillary::format_value(gap) + " m is beyond the rupture distance; allowed: gap <= "
		                            + capillary::format_value(phys->bridge.rupture) + " m + pastRupture (" + capillary::format_value(pastRupture) + " m)");
	phys->active = true;
	if (pendularOwner(current->subdomain, Body::byId(id1, current)->subdomain, Body::byId(id2, current)->subdomain)) {
		nBridges += 1;
		liquidVolume += phys->Vb;
		liquidFormed += phys->Vb;
	}
}

boost::python::dict Law2_ScGeom_PendularPhys_Bridge::liquidTotals() const
{
	refuseWhileRunning("liquidTotals()");
	const auto& current = Omega::instance().getScene();
	Real        films = 0, bridges = 0, fixedBridges = 0;
	for (const auto& b : *current->bodies)
		if (b)
			if (const auto* s = dynamic_cast<const PendularState*>(b->state.get())) films += s->film;
	for (const auto& I : *current->interactions)
		if (const auto* p = dynamic_cast<const PendularPhys*>(I->phys.get()))
			if (p->active) (p->film ? bridges : fixedBridges) += p->Vb;
	boost::python::dict d;
	d["films"]        = films;
	d["bridges"]      = bridges;
	d["removed"]      = liquidRemoved;
	d["total"]        = films + bridges + liquidRemoved;
	d["fixedBridges"] = fixedBridges;
	return d;
}

} // namespace yade
