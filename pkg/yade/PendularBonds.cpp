// PendularBonds: the sharing of the liquid over the pairs within the debonding distance (Richefeu2008
// eq. 13-14 with rule iii), and where the liquid of a broken bond goes under each protocol.
#include "PendularBonds.hpp"
#include "Law2_ScGeom_PendularPhys_Bridge.hpp"
#include "PendularCheck.hpp"
#include "PendularLoop.hpp"
#include "PendularMat.hpp"
#include "bonds.hpp"
#include "transfer.hpp"

#include <core/InteractionLoop.hpp>
#include <pkg/common/InsertionSortCollider.hpp>

#include <array>
#include <map>
#include <stdexcept>
#include <string>

namespace yade {

YADE_PLUGIN((PendularBonds));
CREATE_LOGGER(PendularBonds);

namespace {
	using pendular::radiusOf;

	const std::array<const char*, 4> protocolNames { "update", "particles", "lowest", "neighbours" };

	bool bondsBody(const Body& b)
	{
		const auto* m = dynamic_cast<const PendularMat*>(b.material.get());
		return m && m->bondsMode && dynamic_cast<const PendularState*>(b.state.get());
	}
	// The bond of a real interaction (nullptr if it is not a bonds-mode pair).
	PendularPhys* bondOf(const Interaction& I)
	{
		if (!I.isReal()) return nullptr;
		auto* p = dynamic_cast<PendularPhys*>(I.phys.get());
		return p && p->bonds ? p : nullptr;
	}
	// The first interaction loop of the scene with our law, and the law.
	std::pair<InteractionLoop*, Law2_ScGeom_PendularPhys_Bridge*> lawOf(Scene* scene)
	{
		for (const auto& e : scene->engines)
			if (auto* loop = dynamic_cast<InteractionLoop*>(e.get()))
				for (const auto& f : loop->lawDispatcher->functors)
					if (auto* law = dynamic_cast<Law2_ScGeom_PendularPhys_Bridge*>(f.get())) return { loop, law };
		return { nullptr, nullptr };
	}
	// Gives a potential interaction its geometry (whatever the distance) and its physics, as the
	// interaction loop would at contact; false if the functors give none.
	bool makeReal(Scene* scene, InteractionLoop& loop, shared_ptr<Interaction> I)
	{
		bool        swap = false;
		const auto& b1_  = Body::byId(I->getId1(), scene);
		const auto& b2_  = Body::byId(I->getId2(), scene);
		const auto  geom = loop.geomDispatcher->getFunctor2D(b1_->shape, b2_->shape, swap);
		if (!geom) return false;
		if (swap) I->swapOrder();
		const shared_ptr<Body>& b1     = Body::byId(I->getId1(), scene);
		const shared_ptr<Body>& b2     = Body::byId(I->getId2(), scene);
		const Vector3r          shift2 = scene->isPeriodic ? Vector3r(scene->cell->hSize * I->cellDist.cast<Real>()) : Vector3r::Zero();
		if (!geom->go(b1->shape, b2->shape, *b1->state, *b2->state, shift2, /*force*/ true, I)) return false;
		shared_ptr<Material> m1 = b1->material, m2 = b2->material;
		loop.physDispatcher->explicitAction(m1, m2, I);
		I->iterMadeReal = scene->iter;
		return I->isReal();
	}
	// Adds up to `volume` [m^3] to an existing bond, up to its largest volume; returns what did not fit.
	Real fill(Law2_ScGeom_PendularPhys_Bridge& law, PendularPhys& p, Real volume)
	{
		const Real put = math::min(volume, math::max(p.VbMax - p.Vb, Real(0)));
		if (!(put > 0)) return volume;
		const Real before = p.Vb;
		p.Vb += put;
		try {
			p.buildBridge();
		} catch (const std::exception&) { // cannot happen within [VbMin, VbMax]; the liquid then stays free
			p.Vb = before;
			p.buildBridge();
			return volume;
		}
		law.liquidVolume += put;
		law.liquidFormed += put;
		return volume - put;
	}
	// The smallest gap the collider is sure to list [m]: its verletDist (InsertionSortCollider; a
	// negative value is a fraction of the smallest sphere radius). inf without that collider.
	Real listedGap(Scene* scene)
	{
		for (const auto& e : scene->engines)
			if (const auto* isc = dynamic_cast<const InsertionSortCollider*>(e.get())) {
				if (isc->verletDist >= 0) return isc->verletDist;
				Real rmin = std::numeric_limits<Real>::infinity();
				for (const auto& b : *scene->bodies)
					if (b && dynamic_cast<const Sphere*>(b->shape.get())) rmin = math::min(rmin, radiusOf(b));
				return -isc->verletDist * rmin;
			}
		return std::numeric_limits<Real>::infinity();
	}
} // namespace

PendularBonds* PendularBonds::of(Scene* scene)
{
	for (const auto& e : scene->engines)
		if (auto* engine = dynamic_cast<PendularBonds*>(e.get())) return engine;
	return nullptr;
}

bool PendularBonds::keepsDry(Body::id_t id1, Body::id_t id2) const
{
	return dryFraction > 0 && capillary::bonds::kept_dry(std::uint64_t(id1), std::uint64_t(id2), dryFraction, std::uint64_t(seed));
}

void PendularBonds::postLoad(PendularBonds&)
{
	const std::string c = "PendularBonds";
	int               index = -1;
	for (size_t i = 0; i < protocolNames.size(); ++i)
		if (protocol == protocolNames[i]) index = int(i);
	if (index < 0) throw std::invalid_argument(c + ".protocol = '" + protocol + "' is unknown; allowed: update, particles, lowest, neighbours");
	if (interval < 0) capillary::out_of_range(c + ".interval", Real(interval), "[0, inf)", "steps");
	if (!(dryFraction >= 0 && dryFraction <= 1)) capillary::out_of_range(c + ".dryFraction", dryFraction, "[0, 1]", "");
	if (seed < 0) capillary::out_of_range(c + ".seed", Real(seed), "[0, inf)", "");
	if (!(down.allFinite() && down.norm() > 0))
		throw std::invalid_argument(c + ".down = (" + capillary::format_value(down[0]) + ", " + capillary::format_value(down[1]) + ", "
		                            + capillary::format_value(down[2]) + ") must be a finite non-zero vector");
	protocolIndex = index;
	flagsStale    = true;
}

void PendularBonds::refreshFlags(Scene* current)
{
	for (const auto& I : *current->interactions)
		if (PendularPhys* p = bondOf(*I)) {
			p->keptDry       = keepsDry(I->getId1(), I->getId2());
			p->bondFormation = formsAtContact(I->getId1(), I->getId2());
		}
}

void PendularBonds::action()
{
	if (scene->subdomain != 0) {
		PendularCheck::raiseInStep(scene, "PendularBonds runs in one process: PendularMat.liquid = 'bonds' is not available under yade.mpy");
		return;
	}
	const auto loopLaw = lawOf(scene);
	if (!loopLaw.second) return;
	Law2_ScGeom_PendularPhys_Bridge& law = *loopLaw.second;
	if (flagsStale) {
		refreshFlags(scene);
		flagsStale = false;
	}
	for (const auto& r : law.takeBondReturns())
		place(scene, law, r.id, r.volume, r.partner);
	// The collider's runs (YADE's InsertionSortCollider leaves InteractionContainer::iterColliderLastRun at -1).
	const long runs        = PendularLoop::colliderRuns(*scene);
	const bool colliderRan = runs != colliderRuns;
	colliderRuns           = runs;
	bool due               = nSharings == 0;
	if (protocolIndex == update) due = due || (interval > 0 ? scene->iter - lastSharing >= interval : colliderRan);
	if (!due) return;
	try {
		share(scene, law, 0);
	} catch (const std::exception& e) {
		PendularCheck::raiseInStep(scene, e.what());
	}
}

void PendularBonds::shareNow(Real added)
{
	if (Omega::instance().isRunning())
		throw std::runtime_error("PendularBonds.share() while the simulation runs (O.run()); call O.pause() or O.wait() first");
	Scene* current = Omega::instance().getScene().get();
	if (!(added >= 0 && math::isfinite(added))) capillary::out_of_range("PendularBonds.share: added", added, "[0, inf)", "m^3");
	if (of(current) != this) throw std::invalid_argument("PendularBonds.share(): this engine is not in O.engines of the current scene");
	const auto loopLaw = lawOf(current);
	if (!loopLaw.second) throw std::invalid_argument("PendularBonds.share(): no interaction loop with Law2_ScGeom_PendularPhys_Bridge in O.engines");
	PendularLoop::syncScene(current, true); // the loop reads the changed objects at its next step
	// The candidates are the pairs the collider lists: after O.load (which keeps no potential pair) or a move
	// of the bodies it has not seen, the collider runs here first, as it would at the start of the next step.
	for (const auto& e : current->engines)
		if (auto* collider = dynamic_cast<Collider*>(e.get())) {
			collider->scene = current;
			if (collider->isActivated()) collider->action();
		}
	refreshFlags(current);
	flagsStale = false;
	share(current, *loopLaw.second, added);
	colliderRuns = PendularLoop::colliderRuns(*current); // this sharing saw the collider's last run
}

void PendularBonds::share(Scene* current, Law2_ScGeom_PendularPhys_Bridge& law, Real added)
{
	InteractionLoop& loop = *lawOf(current).first;
	loop.geomDispatcher->scene = current;
	loop.physDispatcher->scene = current;
	loop.geomDispatcher->updateScenePtr();
	loop.physDispatcher->updateScenePtr();
	// All the liquid of the bonds-mode bodies: free, in bonds, and the added liquid.
	Real                        liquid = added;
	std::vector<PendularState*> free;
	for (const auto& b : *current->bodies)
		if (b && bondsBody(*b)) {
			auto* st = static_cast<PendularState*>(b->state.get());
			liquid += st->film;
			free.push_back(st);
		}
	std::vector<PendularPhys*> held;
	for (const auto& I : *current->interactions)
		if (PendularPhys* p = bondOf(*I))
			if (p->active) {
				liquid += p->Vb;
				held.push_back(p);
			}
	// The candidates: every pair of two bonds-mode bodies that the collider lists, not kept dry. A sharing
	// looks at every listed pair once; what it needs of a body (bonds mode, material, radius) is read once.
	struct Member {
		bool            bonds    = false;
		const Material* material = nullptr; // by address: a material outside O.materials has id -1
		Real            radius   = 0;       // radiusOf: inf for a wall or facet
	};
	std::vector<Member> members(current->bodies->size());
	for (const auto& b : *current->bodies)
		if (b && !b->isClump() && bondsBody(*b))
			members[b->id] = { true, b->material.get(), radiusOf(b) };
	// What a potential pair of two spheres needs for its threshold comes from its two materials alone
	// (Ip2_PendularMat_PendularMat_PendularPhys::setLiquid: wet, theta of each, the rupture rule): it is
	// taken from the physics of the first pair of those materials made real here, and the other pairs of
	// them are made real only if they get a bond.
	struct PairParams {
		bool usable = false;
		Real theta1 = 0, theta2 = 0;
		int  rupture = 0;
	};
	std::map<std::pair<const Material*, const Material*>, PairParams> byMaterials;
	struct Candidate {
		shared_ptr<Interaction> I;
		PendularPhys*           phys; // nullptr: a potential pair, made real if it gets a bond
		bool                    made; // made real here: reset again if it gets no bond
	};
	std::vector<Candidate> candidates;
	std::vector<double>    thresholds, cubes;
	for (const auto& I : *current->interactions) {
		const Body::id_t id1 = I->getId1(), id2 = I->getId2();
		if (id1 >= Body::id_t(members.size()) || id2 >= Body::id_t(members.size())) continue;
		const Member &m1 = members[id1], &m2 = members[id2];
		if (!m1.bonds || !m2.bonds || keepsDry(id1, id2)) continue;
		const bool spheres = math::isfinite(m1.radius) && math::isfinite(m2.radius);
		const auto key     = std::make_pair(m1.material, m2.material);
		if (!I->isReal() && spheres) {
			const auto known = byMaterials.find(key);
			if (known != byMaterials.end()) {
				const PairParams& pp = known->second;
				if (!pp.usable) continue;
				// Ig2_Sphere_Sphere_ScGeom's distance, the gap being minus its penetrationDepth.
				const Vector3r shift2 = current->isPeriodic ? Vector3r(current->cell->hSize * I->cellDist.cast<Real>()) : Vector3r::Zero();
				const Real     gap    = (Body::byId(id2, current)->state->pos + shift2 - Body::byId(id1, current)->state->pos).norm() - m1.radius - m2.radius;
				const double   t = capillary::bonds::threshold(capillary::Rupture(pp.rupture), m1.radius, m2.radius, gap, pp.theta1, pp.theta2);
				if (!math::isfinite(t)) continue;
				candidates.push_back({ I, nullptr, true });
				thresholds.push_back(t);
				cubes.push_back(capillary::bonds::cube(m1.radius, m2.radius));
				continue;
			}
		}
		const bool made = !I->isReal();
		if (made && !makeReal(current, loop, I)) {
			I->reset();
			continue;
		}
		auto*       p      = bondOf(*I);
		const auto* g      = dynamic_cast<const ScGeom*>(I->geom.get());
		const bool  usable = p && g && p->wet && p->kn > 0;
		if (made && spheres) byMaterials[key] = { usable, usable ? p->theta1 : 0, usable ? p->theta2 : 0, usable ? p->ruptureIndex : 0 };
		if (!usable) {
			if (made) I->reset();
			continue;
		}
		const double t = capillary::bonds::threshold(
		        capillary::Rupture(p->ruptureIndex), p->R1, p->R2, -g->penetrationDepth, p->theta1, p->theta2);
		if (!math::isfinite(t)) {
			if (made) I->reset();
			continue;
		}
		candidates.push_back({ I, p, made });
		thresholds.push_back(t);
		cubes.push_back(capillary::bonds::cube(p->R1, p->R2));
	}
	const auto resetMade = [&candidates]() {
		for (const auto& c : candidates)
			if (c.made) c.I->reset();
	};
	capillary::bonds::Sharing sharing;
	if (liquid > 0) {
		try {
			sharing = capillary::bonds::share(thresholds, cubes, liquid);
		} catch (const std::invalid_argument&) {
			resetMade();
			throw std::invalid_argument("PendularBonds: no pair of the " + std::to_string(candidates.size()) + " listed can hold the liquid ("
			                            + capillary::format_value(liquid) + " m^3): the bonds-mode bodies are too far apart for its debonding distance");
		}
	}
	if (sharing.bonded.size() != candidates.size()) sharing.bonded.assign(candidates.size(), 0); // no liquid: no bond
	for (size_t i = 0; i < candidates.size(); ++i) {
		Candidate& c = candidates[i];
		if (!sharing.bonded[i] || c.phys) continue;
		if (!makeReal(current, loop, c.I) || !(c.phys = bondOf(*c.I))) {
			resetMade();
			throw std::logic_error("PendularBonds: the pair " + std::to_string(c.I->getId1()) + "-" + std::to_string(c.I->getId2())
			                       + " got no bond physics, unlike the first pair of its materials");
		}
	}
	// Every bond within its model's volumes, and within what the collider lists, before anything changes.
	Real longest = 0;
	for (size_t i = 0; i < candidates.size(); ++i) {
		if (!sharing.bonded[i]) continue;
		const PendularPhys& p = *candidates[i].phys;
		const Real          V = sharing.alpha * cubes[i];
		if (V > p.VbMax * (1 + 1e-12) || V < p.VbMin * (1 - 1e-12)) {
			resetMade();
			capillary::out_of_range("PendularBonds: alpha", sharing.alpha, "[" + capillary::format_value(p.VbMin / cubes[i]) + ", "
			                        + capillary::format_value(p.VbMax / cubes[i]) + "] for the pair " + std::to_string(candidates[i].I->getId1())
			                        + "-" + std::to_string(candidates[i].I->getId2()), "",
			                        "V_b = alpha R^3 must lie within the bridge volumes of the pair (its model's domain and PendularMat.Vb); less liquid, "
			                        "PendularMat.extrapolate, or a model with a larger domain");
		}
		longest = math::max(longest, Real(capillary::rupture_distance(capillary::Rupture(p.ruptureIndex), p.R1, p.R2, V, p.theta1, p.theta2)));
	}
	const Real listed = listedGap(current);
	if (longest > listed) {
		resetMade();
		capillary::out_of_range("InsertionSortCollider.verletDist (collider.verletDist)", listed, "[" + capillary::format_value(longest) + ", inf)", "m",
		                        "PendularBonds needs the collider to list every pair within the longest debonding distance of the sharing");
	}
	// Release every bond and every free volume, then form the new bonds.
	for (PendularState* st : free)
		st->film = 0;
	for (PendularPhys* p : held) {
		law.nBridges -= 1;
		law.liquidVolume -= p->Vb;
		law.liquidReleased += p->Vb;
		p->active  = false;
		p->pending = false;
		p->Vb      = 0;
		p->Fcap    = 0;
	}
	long last = -1;
	for (size_t i = 0; i < candidates.size(); ++i)
		if (sharing.bonded[i]) last = long(i);
	Real sum = 0;
	for (size_t i = 0; i < candidates.size(); ++i) {
		if (!sharing.bonded[i]) {
			if (candidates[i].made) candidates[i].I->reset();
			continue;
		}
		PendularPhys& p = *candidates[i].phys;
		// The last bond takes the rest: sum V_b = the liquid to rounding of the liquid alone (eq. 13).
		p.Vb = long(i) == last ? liquid - sum : sharing.alpha * cubes[i];
		sum += p.Vb;
		p.buildBridge();
		p.transfer1 = capillary::transfer_ratio(capillary::Transfer::diameter, p.R1, p.R2, p.Vb, p.bridge.rupture, p.theta1, p.theta2);
		p.active    = true;
		p.pending   = false;
		law.nBridges += 1;
		law.liquidVolume += p.Vb;
		law.liquidFormed += p.Vb;
	}
	law.zeroEmptyTotals();
	PendularLoop::forgetPotential(current); // some of its potential pairs are bonds now
	alpha       = sharing.alpha;
	nShared     = long(sharing.count);
	nCandidates = long(candidates.size());
	reach       = longest;
	nSharings += 1;
	lastSharing = current->iter;
}

void PendularBonds::place(Scene* current, Law2_ScGeom_PendularPhys_Bridge& law, Body::id_t id, Real volume, Body::id_t partner)
{
	if (!(volume > 0)) return;
	if (!current->bodies->exists(id)) {
		law.giveBack(current, id, volume);
		return;
	}
	const shared_ptr<Body>& body = Body::byId(id, current);
	const Real              R    = radiusOf(body);
	Real                    rest = volume;
	if ((protocolIndex == lowest || protocolIndex == neighbours) && math::isfinite(R)) {
		const Vector3r           d = down.normalized();
		std::vector<PendularPhys*> targets;
		std::vector<Real>          weights;
		PendularPhys*              lowestBond = nullptr;
		Real                       depth      = 0;
		for (const auto& entry : body->intrs) {
			const Interaction& I = *entry.second;
			PendularPhys*      p = bondOf(I);
			if (!p || !p->active || entry.first == partner) continue;
			if (protocolIndex == lowest) {
				// Richefeu2008 section 4.2: the lowest contact in the particle's lower hemisphere.
				const auto*    g      = static_cast<const ScGeom*>(I.geom.get());
				const Vector3r shift  = current->isPeriodic ? Vector3r(current->cell->hSize * I.cellDist.cast<Real>()) : Vector3r::Zero();
				const Vector3r centre = I.getId1() == id ? body->state->pos : Vector3r(body->state->pos + shift);
				const Real     h      = (g->contactPoint - centre).dot(d);
				if (h > depth) {
					depth      = h;
					lowestBond = p;
				}
			} else {
				// Richefeu2008 section 2.2: the remaining bonds, in proportion to the diameters of the partners.
				const Real Rp = radiusOf(Body::byId(entry.first, current));
				targets.push_back(p);
				weights.push_back(math::isfinite(Rp) ? Rp : 2 * R);
			}
		}
		if (lowestBond) rest = fill(law, *lowestBond, volume);
		if (!targets.empty()) {
			Real total = 0;
			for (Real w : weights)
				total += w;
			rest = 0;
			for (size_t i = 0; i < targets.size(); ++i)
				rest += fill(law, *targets[i], volume * weights[i] / total);
		}
		if (rest < volume) nPlaced += 1;
	}
	if (rest > 0) {
		law.giveBack(current, id, rest);
		nFree += 1;
	}
}

} // namespace yade
