// Ip2_PendularMat_PendularMat_PendularPhys: mixing rules of two PendularMat into the contact
// parameters and the bridge of a PendularPhys, and the errors and time steps it keeps for PendularCheck.
#include "Ip2_PendularMat_PendularMat_PendularPhys.hpp"
#include "CriticalDt.hpp"
#include "PendularBonds.hpp"
#include "PendularCheck.hpp"
#include "PendularLoop.hpp"
#include "PendularState.hpp"
#include "transfer.hpp"
#include "young_laplace_table.hpp"

#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace yade {

YADE_PLUGIN((Ip2_PendularMat_PendularMat_PendularPhys));
CREATE_LOGGER(Ip2_PendularMat_PendularMat_PendularPhys);

namespace {
	using pendular::isSet;
	using pendular::radiusOf;

	// The value a pair table lists for materials id1 and id2, in either order; NaN if it lists none.
	Real listed(const shared_ptr<MatchMaker>& table, int id1, int id2)
	{
		if (!table) return NaN;
		for (const Vector3r& m : table->matches)
			if ((int(m[0]) == id1 && int(m[1]) == id2) || (int(m[0]) == id2 && int(m[1]) == id1)) return m[2];
		return NaN;
	}
	// Every match of a table: two material ids (integers >= 0) and a value inside `allows`.
	template <class Allows> void checkTable(const shared_ptr<MatchMaker>& table, const char* name, Allows allows, const char* range, const char* unit)
	{
		if (!table) return;
		for (const Vector3r& m : table->matches) {
			const std::string where = std::string("Ip2_PendularMat_PendularMat_PendularPhys.") + name + ": the match (" + capillary::format_value(m[0]) + ", "
			        + capillary::format_value(m[1]) + ", " + capillary::format_value(m[2]) + ")";
			for (const Real id : { m[0], m[1] })
				if (!(id >= 0 && id == math::round(id))) throw std::invalid_argument(where + " has a material id that is not an integer >= 0");
			if (!allows(m[2])) throw std::invalid_argument(where + " has the value " + capillary::format_value(m[2]) + " " + unit + ", outside the allowed range " + range);
		}
	}
} // namespace

void Ip2_PendularMat_PendularMat_PendularPhys::postLoad(Ip2_PendularMat_PendularMat_PendularPhys&)
{
	try {
		checkTable(frictionAngle, "frictionAngle", [](Real v) { return v >= 0 && v < Mathr::HALF_PI; }, "[0, pi/2)", "rad");
		checkTable(rollingFriction, "rollingFriction", [](Real v) { return v >= 0 && math::isfinite(v); }, "[0, inf)", "m");
		// The range of en depends on the materials' normalDamping: the lower bound of the approach-only dashpot is checked per pair.
		checkTable(en, "en", [](Real v) { return v > pendular::minRestitution(false) && v <= 1; }, "(exp(-2) = 0.1353, 1]", "-");
	} catch (const std::invalid_argument&) {
		// A rejected table is rolled back, so that it does not make every later assignment fail.
		frictionAngle = goodTables[0], rollingFriction = goodTables[1], en = goodTables[2];
		throw;
	}
	goodTables = { frictionAngle, rollingFriction, en };
}

void Ip2_PendularMat_PendularMat_PendularPhys::go(const shared_ptr<Material>& b1, const shared_ptr<Material>& b2, const shared_ptr<Interaction>& I)
{
	if (I->phys) return;
	const auto& m1    = static_cast<const PendularMat&>(*b1);
	const auto& m2    = static_cast<const PendularMat&>(*b2);
	const auto& body1 = Body::byId(I->getId1(), scene);
	const auto& body2 = Body::byId(I->getId2(), scene);
	auto        phys  = shared_ptr<PendularPhys>(new PendularPhys());
	I->phys           = phys;
	// No exception may leave InteractionLoop's OpenMP loop: errors are recorded for PendularCheck.
	try {
		setContact(phys, m1, m2, body1, body2);
	} catch (const std::exception& e) {
		// kn stays 0: the Law2 resets the interaction, so this error comes again at the next step
		// instead of leaving a pair that passes through without a contact force.
		report(e.what(), *I);
		return;
	}
	try {
		setLiquid(phys, m1, m2, body1, body2);
	} catch (const std::exception& e) {
		phys->wet    = false; // the bridge is refused, the contact law stays
		phys->viscous.reset();
		report(e.what(), *I);
	}
	const Real                        dt = pendular::pairCriticalDt(*phys, *body1, *body2);
	const std::lock_guard<std::mutex> lock(dtMutex);
	if (dt < newCriticalDt.dt) newCriticalDt = { dt, I->getId1(), I->getId2() };
}

long Ip2_PendularMat_PendularMat_PendularPhys::updateContacts()
{
	if (Omega::instance().isRunning())
		throw std::runtime_error("updateContacts() while the simulation runs (O.run()); call O.pause() or O.wait() first");
	Scene* current = Omega::instance().getScene().get();
	PendularLoop::syncScene(current, true); // the records into the objects; the loop reads them again at its next step
	// Every pair first on copies, so that a refused one leaves all as they were.
	std::vector<std::pair<shared_ptr<PendularPhys>, shared_ptr<PendularPhys>>> updated;
	for (const auto& I : *current->interactions) {
		if (!I->isReal()) continue;
		const auto phys = YADE_PTR_DYN_CAST<PendularPhys>(I->phys);
		const auto& b1 = Body::byId(I->getId1(), current);
		const auto& b2 = Body::byId(I->getId2(), current);
		const auto* m1 = b1 ? dynamic_cast<const PendularMat*>(b1->material.get()) : nullptr;
		const auto* m2 = b2 ? dynamic_cast<const PendularMat*>(b2->material.get()) : nullptr;
		if (!phys || !m1 || !m2) continue;
		auto copy = shared_ptr<PendularPhys>(new PendularPhys(*phys));
		try {
			setContact(copy, *m1, *m2, b1, b2);
		} catch (const std::exception& e) {
			throw std::invalid_argument(std::string(e.what()) + " (interaction " + std::to_string(I->getId1()) + "-" + std::to_string(I->getId2())
			                            + "; no interaction was changed)");
		}
		updated.emplace_back(phys, copy);
	}
	for (auto& u : updated) {
		PendularPhys& p = *u.first;
		const PendularPhys& c = *u.second;
		p.kn = c.kn, p.cn = c.cn, p.ks = c.ks, p.cs = c.cs;
		p.tangensOfFrictionAngle = c.tangensOfFrictionAngle;
		p.rollingFriction        = c.rollingFriction;
		p.approachDamping        = c.approachDamping;
		p.viscousFriction        = c.viscousFriction;
	}
	return long(updated.size());
}

void Ip2_PendularMat_PendularMat_PendularPhys::report(const std::string& what, const Interaction& I)
{
	const std::string                 message = what + " (interaction " + std::to_string(I.getId1()) + "-" + std::to_string(I.getId2()) + ")";
	const std::lock_guard<std::mutex> lock(errorMutex);
	if (errorPending && errorScene == scene && errorIter == scene->iter) return; // the first error of the step is raised
	errorPending     = true;
	error            = message;
	errorScene       = scene;
	errorIter        = scene->iter;
	// Without PendularCheck the run stops after this step; PendularCheck raises instead and puts
	// stopAtIter back, so that a user who catches the error can go on running.
	stopAtIterBefore  = scene->stopAtIter;
	scene->stopAtIter = scene->iter + 1;
	LOG_ERROR(message);
}

std::string Ip2_PendularMat_PendularMat_PendularPhys::takeError(Scene* current)
{
	const std::lock_guard<std::mutex> lock(errorMutex);
	if (!errorPending) return "";
	errorPending = false;
	if (errorScene != current || errorIter != current->iter) return ""; // left by a step without PendularCheck
	current->stopAtIter = stopAtIterBefore;
	return error;
}

Ip2_PendularMat_PendularMat_PendularPhys::PairDt Ip2_PendularMat_PendularMat_PendularPhys::takeCriticalDt()
{
	const std::lock_guard<std::mutex> lock(dtMutex);
	const PairDt                      taken = newCriticalDt;
	newCriticalDt                           = PairDt {};
	return taken;
}

Real Ip2_PendularMat_PendularMat_PendularPhys::criticalDt(Body::id_t id1, Body::id_t id2)
{
	scene              = Omega::instance().getScene().get(); // called from Python, outside any loop
	const auto& bodies = scene->bodies;
	if (!bodies->exists(id1) || !bodies->exists(id2) || id1 == id2)
		throw std::invalid_argument("criticalDt: need two different existing bodies, got ids " + std::to_string(id1) + " and " + std::to_string(id2));
	const auto& body1 = (*bodies)[id1];
	const auto& body2 = (*bodies)[id2];
	const auto* m1    = dynamic_cast<const PendularMat*>(body1->material.get());
	const auto* m2    = dynamic_cast<const PendularMat*>(body2->material.get());
	if (!m1 || !m2)
		throw std::invalid_argument("criticalDt: bodies " + std::to_string(id1) + " and " + std::to_string(id2) + " must both have a PendularMat");
	auto phys = shared_ptr<PendularPhys>(new PendularPhys());
	setContact(phys, *m1, *m2, body1, body2);
	try {
		setLiquid(phys, *m1, *m2, body1, body2);
	} catch (const std::exception&) { // a refused bridge: the pair has the contact law alone, as in go()
		phys->viscous.reset();
	}
	return pendular::pairCriticalDt(*phys, *body1, *body2);
}

void Ip2_PendularMat_PendularMat_PendularPhys::setContact(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	const Real massR = pendular::effectiveMass(*body1, *body2);
	const bool byTime = isSet(m1.tc) && isSet(m1.en) && isSet(m1.et) && isSet(m2.tc) && isSet(m2.en) && isSet(m2.et);
	const bool byStiff = isSet(m1.kn) && isSet(m1.cn) && isSet(m1.ks) && isSet(m1.cs) && isSet(m2.kn) && isSet(m2.cn) && isSet(m2.ks)
	        && isSet(m2.cs);
	if (byTime == byStiff) {
		auto given = [](const PendularMat& m) {
			return "material " + std::to_string(m.id) + ": tc = " + capillary::format_value(m.tc) + ", en = " + capillary::format_value(m.en) + ", et = " + capillary::format_value(m.et)
			        + ", kn = " + capillary::format_value(m.kn) + ", cn = " + capillary::format_value(m.cn) + ", ks = " + capillary::format_value(m.ks) + ", cs = " + capillary::format_value(m.cs);
		};
		throw std::invalid_argument(
		        "PendularMat: give either tc, en, et or kn, cn, ks, cs on both materials (" + given(m1) + "; " + given(m2) + ")");
	}
	for (const auto& [name, a, b] : { std::tuple<const char*, std::string, std::string> { "normalDamping", m1.normalDamping, m2.normalDamping },
	                                  { "friction", m1.friction, m2.friction } })
		if (a != b)
			throw std::invalid_argument(std::string("PendularMat.") + name + " must be equal on both materials of a contact; got '" + a + "' and '" + b + "'");
	phys->approachDamping = m1.approachDamping;
	phys->viscousFriction = m1.viscousFriction;
	const Real pairEn = listed(en, m1.id, m2.id);
	if (isSet(pairEn)) {
		const std::string pair = "Ip2_PendularMat_PendularMat_PendularPhys.en lists " + capillary::format_value(pairEn) + " for materials "
		        + std::to_string(m1.id) + " and " + std::to_string(m2.id);
		if (!byTime) throw std::invalid_argument(pair + ", which are given by kn, cn, ks, cs; a restitution per pair needs tc, en, et on both");
		if (!(pairEn > pendular::minRestitution(m1.approachDamping)))
			throw std::invalid_argument(pair + ", outside the allowed range (exp(-1) = 0.3679, 1] of normalDamping='approach'");
	}
	if (byTime) {
		// (the restitution is `e`: `en` is the pair table)
		const Real tc = (m1.tc + m2.tc) / 2, e = isSet(pairEn) ? pairEn : (m1.en + m2.en) / 2, et = (m1.et + m2.et) / 2;
		if (!(massR > 0))
			throw std::invalid_argument(
			        "PendularMat with tc, en, et: bodies need a positive mass (masses " + capillary::format_value(body1->state->mass) + " and "
			        + capillary::format_value(body2->state->mass) + " kg)");
		const Real omega = Mathr::PI / tc;                                            // half period of the damped oscillation = tc
		const Real x     = (m1.en == m2.en && !isSet(pairEn)) ? m1.dampingRatioN : pendular::dampingRatioFor(e, m1.approachDamping); // beta / omega
		phys->kn         = massR * omega * omega * (1 + x * x);
		phys->cn         = 2 * massR * omega * x;
		// Tangential: YADE's ViscElMat rule (Pournin2001 with the factor 2/7 of a rolling sphere).
		const Real xt = -math::log(et) / Mathr::PI;
		phys->ks      = 2. / 7. * massR * omega * omega * (1 + xt * xt);
		phys->cs      = 2. / 7. * 2 * massR * omega * xt;
	} else {
		auto series = [](Real a, Real b) { return (a > 0 && b > 0) ? a * b / (a + b) : 0; };
		phys->kn    = series(m1.kn, m2.kn);
		phys->cn    = series(m1.cn, m2.cn);
		phys->ks    = series(m1.ks, m2.ks);
		phys->cs    = series(m1.cs, m2.cs);
	}
	const Real pairFriction = listed(frictionAngle, m1.id, m2.id), pairRolling = listed(rollingFriction, m1.id, m2.id);
	phys->tangensOfFrictionAngle = math::tan(isSet(pairFriction) ? pairFriction : math::min(m1.frictionAngle, m2.frictionAngle));
	phys->rollingFriction        = isSet(pairRolling) ? pairRolling : (m1.rollingFriction + m2.rollingFriction) / 2;
}

void Ip2_PendularMat_PendularMat_PendularPhys::setLiquid(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	for (const auto& bm : { std::make_pair(body1, &m1), std::make_pair(body2, &m2) }) {
		const auto* state = dynamic_cast<const PendularState*>(bm.first->state.get());
		if (state && state->film > 0 && !bm.second->filmMode)
			throw std::invalid_argument("PendularState.film = " + capillary::format_value(state->film) + " m^3 on body " + std::to_string(bm.first->id)
			                            + ", whose material has liquid = '" + bm.second->liquid + "'; films need liquid = 'film' or 'bonds'");
	}
	phys->wet = m1.wet && m2.wet;
	if (phys->wet) {
		auto mustMatch = [&](const char* name, const std::string& a, const std::string& b) {
			if (a != b)
				throw std::invalid_argument(
				        std::string("PendularMat.") + name + " must be equal on both materials of a bridge; got '" + a + "' and '" + b + "'");
		};
		mustMatch("model", m1.model, m2.model);
		if (m1.ruptureId != m2.ruptureId || m1.dynamicRupture != m2.dynamicRupture) mustMatch("rupture", m1.rupture, m2.rupture); // pitois = willett+pitois
		mustMatch("forceInContact", m1.forceInContact ? "True" : "False", m2.forceInContact ? "True" : "False");
		// Compared as values: 1e-7 and 4e-7 N are different, and the message shows both exactly.
		if (m1.linearFmax != m2.linearFmax) mustMatch("linearFmax", capillary::format_value(m1.linearFmax), capillary::format_value(m2.linearFmax));
		if (m1.linearKc != m2.linearKc) mustMatch("linearKc", capillary::format_value(m1.linearKc), capillary::format_value(m2.linearKc));
		mustMatch("calibrateFrom", m1.calibrateFrom, m2.calibrateFrom);
		mustMatch("extrapolate", m1.extrapolate ? "True" : "False", m2.extrapolate ? "True" : "False");
		if ((m1.eta > 0) != (m2.eta > 0))
			throw std::invalid_argument("PendularMat.eta must be > 0 on both materials of a viscous bridge or 0 on both; got " + capillary::format_value(m1.eta)
			                            + " and " + capillary::format_value(m2.eta) + " Pa s (the liquid's viscosity; a material left at 0 would halve it)");
		if (m1.eta > 0) {
			mustMatch("viscousNormal", m1.viscousNormal, m2.viscousNormal);
			if (m1.viscousSmin != m2.viscousSmin)
				mustMatch("viscousSmin", capillary::format_value(m1.viscousSmin), capillary::format_value(m2.viscousSmin));
		}
		phys->R1             = radiusOf(body1);
		phys->R2             = radiusOf(body2);
		phys->swapped        = math::isinf(phys->R1);
		if (phys->swapped) { // keep the sphere first: the kernels take R2 = inf for a wall
			std::swap(phys->R1, phys->R2);
			phys->theta1 = m2.theta;
			phys->theta2 = m1.theta;
		} else {
			phys->theta1 = m1.theta;
			phys->theta2 = m2.theta;
		}
		if (math::isinf(phys->R1)) throw std::invalid_argument("PendularMat: a liquid bridge needs at least one sphere");
		phys->Vb             = (m1.Vb + m2.Vb) / 2;
		phys->gamma          = (m1.gamma + m2.gamma) / 2;
		phys->modelIndex     = int(m1.modelId);
		phys->ruptureIndex   = int(m1.ruptureId);
		phys->calibrateIndex = int(m1.calibrateId);
		phys->extrapolate    = m1.extrapolate;
		phys->linearFmax     = m1.linearFmax;
		phys->linearKc       = m1.linearKc;
		phys->forceInContact = m1.forceInContact;
		phys->eta            = (m1.eta + m2.eta) / 2;
		phys->viscousIndex   = phys->eta > 0 ? int(m1.viscousId) : -1;
		phys->viscousSmin    = m1.viscousSmin;
		phys->dynamicRupture = m1.dynamicRupture; // both wet: validated with eta > 0
		if (m1.filmMode != m2.filmMode || m1.bondsMode != m2.bondsMode) mustMatch("liquid", m1.liquid, m2.liquid);
		if (!m1.filmMode) {
			phys->buildBridge();
			return;
		}
		if (!m1.bondsMode) {
			mustMatch("formation", m1.formation, m2.formation);
			mustMatch("transfer", m1.transfer, m2.transfer);
		}
		setFilm(phys, m1, body1, body2);
		if (m1.bondsMode) setBonds(phys, m1, body1, body2);
	}
}

// Film mode: the volume range of the pair's bridges, checked once with the largest (model, contact
// angles, size ratio, transfer rule); the bridge itself is built when it forms (settleFilms).
void Ip2_PendularMat_PendularMat_PendularPhys::setFilm(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	for (const auto& b : { body1, body2 })
		if (!dynamic_cast<const PendularState*>(b->state.get()))
			throw std::invalid_argument("PendularMat.liquid = 'film' needs a PendularState on body " + std::to_string(b->id) + ", which has a "
			                            + b->state->getClassName() + " (create it with utils.sphere(..., material=mat) or give it mat.newAssocState())");
	bool checked = false;
	for (const auto& e : scene->engines)
		if (dynamic_cast<const PendularCheck*>(e.get())) checked = true;
	if (!checked)
		throw std::invalid_argument("PendularMat.liquid = 'film' needs a PendularCheck engine after the interaction loop, which forms the bridges and "
		                            "moves the liquid at the end of each step (yade_capillary.scene.engines adds it)");
	for (const auto& b : { body1, body2 }) {
		const auto& st = static_cast<const PendularState&>(*b->state);
		if (math::isinf(radiusOf(b)) && st.film > 0 && !(st.filmArea > 0))
			throw std::invalid_argument("PendularState.film = " + capillary::format_value(st.film) + " m^3 on body " + std::to_string(b->id)
			                            + ", a wall or facet with filmArea = 0, which holds no liquid; give it the wettable area filmArea > 0 [m^2]");
	}
	// Bonds share their liquid in proportion to the diameters (Richefeu2008 section 3.2) and form at contact.
	const capillary::Transfer transfer = m1.bondsMode ? capillary::Transfer::diameter : m1.transferId;
	phys->film          = true;
	phys->filmFormation = m1.bondsMode ? false : m1.filmFormation;
	phys->transferIndex = int(transfer);
	// V* range: the model's domain (Plausible with extrapolate), and the exact transfer table's.
	Real r1, r2;
	capillary::equivalent_pair(phys->R1, phys->R2, r1, r2);
	const Real               R = capillary::harmonic_mean_radius(r1, r2); // of V* = V/R^3
	const capillary::Domain& d = capillary::info(capillary::Model(phys->modelIndex)).domain;
	Real vstarMin = phys->extrapolate ? capillary::Plausible::vstar_min : d.vstar_min, vstarMax = phys->extrapolate ? capillary::Plausible::vstar_max : d.vstar_max;
	if (transfer == capillary::Transfer::exact) {
		vstarMin = math::max(vstarMin, math::exp(capillary::yltable::lnv_min));
		vstarMax = math::min(vstarMax, math::exp(capillary::yltable::lnv_max));
	}
	const Real R3 = R * R * R;
	phys->VbMin   = vstarMin * R3;
	phys->VbMax   = math::min(phys->Vb, vstarMax * R3);
	if (!(phys->VbMax >= phys->VbMin))
		capillary::out_of_range("PendularMat.Vb (the mean of the two materials)", phys->Vb, "[" + capillary::format_value(phys->VbMin) + ", inf) for this pair", "m^3",
		                        "with liquid='film' Vb is the largest bridge volume; the smallest is V* = " + capillary::format_value(vstarMin)
		                                + " times R^3 (the domain of the model and of the transfer rule)");
	// The largest bridge checks everything but its volume: model, angles, ratio, transfer rule.
	phys->Vb = phys->VbMax;
	phys->buildBridge();
	try {
		capillary::transfer_ratio(capillary::Transfer(phys->transferIndex), phys->R1, phys->R2, phys->Vb, phys->bridge.rupture, phys->theta1, phys->theta2);
	} catch (const std::exception& e) {
		throw std::invalid_argument("PendularMat.transfer = '" + std::string(capillary::transfer_rules()[int(transfer)].name) + "' cannot split this pair's bridges (PendularMat.theta " + capillary::format_value(phys->theta1)
		                            + " and " + capillary::format_value(phys->theta2) + " rad, radii " + capillary::format_value(phys->R1) + " and "
		                            + capillary::format_value(phys->R2) + " m): " + e.what() + "; another rule: " + capillary::transfer_names());
	}
	phys->Vb = 0;
	phys->viscous.reset();
}

// Bonds mode: the pair's flags from the scene's PendularBonds (Richefeu2008 section 2.4); its volume
// comes from the engine's sharing or, at a new contact, from the free liquid of its bodies.
void Ip2_PendularMat_PendularMat_PendularPhys::setBonds(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	if (capillary::info(capillary::Model(phys->modelIndex)).own_rupture)
		throw std::invalid_argument("PendularMat.liquid = 'bonds' shares the liquid by the debonding distance of the rupture rule; model '" + m1.model
		                            + "' has its own range instead; use another model (the closed forms with rupture lian, willett or willett_elskamp)");
	const PendularBonds* engine = PendularBonds::of(scene);
	if (!engine)
		throw std::invalid_argument("PendularMat.liquid = 'bonds' needs a PendularBonds engine after PendularCheck, which shares the liquid and "
		                            "places the liquid of broken bonds (e.g. yade_capillary.scene.engines(extra=[PendularBonds()]))");
	phys->bonds         = true;
	phys->keptDry       = engine->keepsDry(body1->id, body2->id);
	phys->bondFormation = engine->formsAtContact(body1->id, body2->id);
}

} // namespace yade
