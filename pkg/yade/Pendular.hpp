// YADE layer of yade-capillary: material, interaction physics, Ip2 and Law2 for wet (pendular)
// granular matter. The capillary formulas live in pkg/kernels/models.hpp; this file only wires
// them into YADE's class factory.
#pragma once

#include "YadeHeaders.hpp"
#include <core/GlobalEngine.hpp>
#include "film.hpp"
#include "models.hpp"
#include "transfer.hpp"
#include "viscous.hpp"

#include <limits>
#include <memory>
#include <mutex>
#include <type_traits>
#include <vector>

namespace yade {

// The liquid a body carries (PendularMat.liquid = 'film'): every body of a PendularMat gets this state
// (PendularMat.newAssocState, used by utils.sphere, utils.wall, utils.facet, ...).
class PendularState : public State {
	Real lastFilm = 0, lastFilmArea = 0; // the values after the last successful check (a rejected assignment is rolled back)

public:
	void postLoad(PendularState&);
	// The film thickness [m]: Elskamp2018 eq. (34) on a sphere of radius R, film/filmArea on a wall or
	// facet (R = inf), 0 on a wall that holds no film.
	Real thickness(Real R) const;
	// A wall or facet holds liquid only on a wettable area; a sphere always does.
	bool holds(Real R) const { return !math::isinf(R) || filmArea > 0; }
	virtual ~PendularState() = default;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR(PendularState, State,
		"State of a body of a :yref:`PendularMat`: the liquid it carries when the material's ``liquid`` is ``'film'`` "
		"(Elskamp2018 section 2.2.1). New bridges take their liquid from the films of both bodies (Shi & McCarthy, "
		"Elskamp2018 eq. 7-10); a breaking bridge gives it back by the transfer ratio (PendularMat.transfer).",
		((Real, film, 0, Attr::triggerPostLoad, "Free liquid on the body [m^3], [0, 1e9] (at most a body of 1 km): the film, not counting the liquid in its bridges. Only with PendularMat.liquid = 'film' (an error at the first interaction otherwise). Written by the bridges at the end of each step (PendularCheck)."))
		((Real, filmArea, 0, Attr::triggerPostLoad, "Walls and facets: the wettable area [m^2], 0 or [1e-18, 1e6], over which their film spreads (film thickness W = film/filmArea, Elskamp2018 eq. 10). 0 (the default): the wall holds no liquid, gives none to a bridge and, at rupture, leaves the whole bridge to the sphere. Unused on spheres.")),
		createIndex();
	);
	// clang-format on
	REGISTER_CLASS_INDEX(PendularState, State);
};
REGISTER_SERIALIZABLE(PendularState);

class PendularMat : public Material {
public:
	capillary::Model   modelId       = capillary::Model::willett_full; // resolved from `model` by postLoad
	capillary::Rupture ruptureId     = capillary::Rupture::willett;
	capillary::Model   calibrateId   = capillary::Model::willett_full;
	bool               dynamicRupture = false; // `rupture` ends with pitois (Elskamp2018 eq. 33)
	capillary::NormalViscous viscousId = capillary::NormalViscous::pitois;
	bool               filmMode      = false; // liquid == "film"
	bool               filmFormation = false; // formation == "films"
	capillary::Transfer transferId   = capillary::Transfer::exact;
	Real               dampingRatioN = 0; // beta/omega for `en`, see dampingRatioFor() in Pendular.cpp
	void               postLoad(PendularMat&);

private:
	// Attribute values after the last successful check: a rejected assignment is rolled back, so
	// one bad value does not make every later assignment fail.
	struct Checked {
		Real        tc, en, et, kn, cn, ks, cs, frictionAngle, Vb, gamma, theta, linearFmax, linearKc, eta, viscousSmin;
		bool        wet, forceInContact, extrapolate;
		std::string model, rupture, calibrateFrom, viscousNormal, liquid, formation, transfer;
	};
	Checked checked() const;
	void    restore(const Checked&);
	void    validate();
	Checked lastGood;

public:
	shared_ptr<State> newAssocState() const override { return shared_ptr<State>(new PendularState); }
	virtual ~PendularMat() = default;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR(PendularMat, Material,
		"Material of yade-capillary: linear viscoelastic contact (Gladkyy2014 eq. 3-4) with Coulomb friction, and optionally "
		"a pendular liquid bridge that forms when two particles touch and breaks beyond the rupture distance. "
		"Give either (:yref:`tc<PendularMat.tc>`, :yref:`en<PendularMat.en>`, :yref:`et<PendularMat.et>`) or "
		"(:yref:`kn<PendularMat.kn>`, :yref:`cn<PendularMat.cn>`, :yref:`ks<PendularMat.ks>`, :yref:`cs<PendularMat.cs>`). "
		"Set the liquid parameters first, then ``wet=True``; every value is checked when it is assigned, "
		"combinations of two materials when their first interaction is created.",
		((Real, tc, NaN, Attr::triggerPostLoad, "Contact duration [s], (0, inf); NaN if kn, cn, ks, cs are given. The normal stiffness and damping make the half period of the damped oscillation equal to tc."))
		((Real, en, NaN, Attr::triggerPostLoad, "Normal restitution coefficient [-], (exp(-2), 1]. Exact for a binary collision including the rule that the contact never attracts (Schwager & Poeschel 2007), unlike the textbook formula."))
		((Real, et, NaN, Attr::triggerPostLoad, "Tangential restitution coefficient [-], (0, 1]; sets ks = 2/7 kn-equivalent and cs as in YADE's ViscElMat."))
		((Real, kn, NaN, Attr::triggerPostLoad, "Normal stiffness of this material [N/m], (0, inf); two materials combine in series. NaN if tc, en, et are given."))
		((Real, cn, NaN, Attr::triggerPostLoad, "Normal damping of this material [N s/m], [0, inf); combined in series."))
		((Real, ks, NaN, Attr::triggerPostLoad, "Tangential stiffness of this material [N/m], [0, inf); combined in series."))
		((Real, cs, NaN, Attr::triggerPostLoad, "Tangential damping of this material [N s/m], [0, inf); combined in series."))
		((Real, frictionAngle, 0.5, Attr::triggerPostLoad, "Contact friction angle [rad], [0, pi/2); the smaller of two materials is used."))
		((bool, wet, false, Attr::triggerPostLoad, "True: liquid bridges form at contacts of two wet materials. Requires Vb > 0 and gamma > 0."))
		((Real, Vb, 0, Attr::triggerPostLoad, "Liquid bridge volume [m^3], (0, inf) when wet. Two materials: arithmetic mean. With liquid='film': the largest bridge volume (a larger Shi-McCarthy volume is capped, the rest stays on the films)."))
		((Real, gamma, 0, Attr::triggerPostLoad, "Surface tension [N/m], (0, inf) when wet. Two materials: arithmetic mean."))
		((Real, theta, 0, Attr::triggerPostLoad, "Contact angle [rad], [0, pi/2). Two materials: each keeps its own; the force models use the angle whose cosine is the mean of the cosines (Elskamp2018 eq. 14-15, closer to the exact bridge than the mean angle), the lian and willett rupture rules the mean angle, willett_elskamp both."))
		((std::string, model, "willett_full", Attr::triggerPostLoad, "Capillary bridge model, one of:" CAPILLARY_MODEL_NAMES_LITERAL " (yade_capillary.kernels.models() lists each with its source and validity domain; young_laplace_table is the exact bridge, tabulated, with the exact rupture distance). A bridge outside its model's domain is refused unless extrapolate=True; a contact angle outside it is refused when the material is wet. Must be equal on both materials."))
		((std::string, rupture, "willett", Attr::triggerPostLoad, "Rupture rule: lian ((1+theta/2) V^(1/3)), willett (Gladkyy2014 eq. 2), willett_elskamp (Elskamp2018 eq. 32); linear_irreversible and young_laplace_table use their own range (fmax/kc, the exact rupture). Append +pitois (e.g. willett+pitois) for the dynamic rupture distance S_rup (1 + sqrt(|v1 - v2| eta/gamma)) (Pitois et al. 2001, Elskamp2018 eq. 33) on top of the static rule (or the model's own range); pitois alone means willett+pitois. +pitois needs eta > 0. Beyond the static distance the model's formula is continued, floored at 0 and capped at the force at the static distance (young_laplace_table keeps that force). Must mean the same rule on both materials."))
		((bool, forceInContact, false, Attr::triggerPostLoad, "True: the bridge force at contact F(0) also acts during overlap (Richefeu2008, Roy); False: it is off during overlap (Gladkyy2014 eq. 4). Must be equal on both materials."))
		((Real, linearFmax, 0, Attr::triggerPostLoad, "linear_irreversible: maximum adhesive force [N], (0, inf); 0 (with linearKc = 0) to calibrate from calibrateFrom."))
		((Real, linearKc, 0, Attr::triggerPostLoad, "linear_irreversible: adhesive stiffness [N/m], (0, inf); 0 (with linearFmax = 0) to calibrate from calibrateFrom."))
		((std::string, calibrateFrom, "willett_full", Attr::triggerPostLoad, "linear_irreversible: model whose maximum force and adhesive energy the linear law matches, per bridge (Roy section 4.2)."))
		((Real, eta, 0, Attr::triggerPostLoad, "Dynamic viscosity of the liquid [Pa s], [0, 1e9]. 0 (the default): no viscous force is evaluated. > 0: a bridge adds the normal viscous force (viscousNormal) and Goldman's tangential force and moments (Elskamp2018 eq. 28, 29), in contact and separated. Two materials: arithmetic mean; both must be > 0 or both 0 (a wall left at 0 would halve the viscosity of its bridges)."))
		((std::string, viscousNormal, "pitois", Attr::triggerPostLoad, "Normal viscous force with eta > 0: pitois (Pitois et al. 2000, Elskamp2018 eq. 26, finite bridge volume; the default) or adams_perchard (Elskamp2018 eq. 25). Must be equal on both materials."))
		((Real, viscousSmin, 0.001, Attr::triggerPostLoad, "S_min / r* [-], [1e-12, 1]: the viscous forces are evaluated at the separation max(S, 0) + S_min, S_min = viscousSmin r*, r* = R1 R2/(R1 + R2) (R1 for a wall), so that they stay finite at contact (Elskamp2018 after eq. 29: 0.001). Must be equal on both materials."))
		((std::string, liquid, "fixed", Attr::triggerPostLoad, "Where the liquid is: fixed (the default: each bridge has the volume Vb, created at formation and destroyed at rupture, Gladkyy2014) or film (the bodies carry it, PendularState.film: a bridge takes its volume from both films by Shi & McCarthy, Elskamp2018 eq. 7-10, capped at Vb and at the largest V* of the model's domain and of the exact transfer table; it forms one step after the pair qualifies, when PendularCheck has shared each film among all the bridges formed on it in that step, Elskamp2018 section 2.2.1; a volume below the smallest V* of those domains forms no bridge; at rupture the volume goes back to the two films by the transfer rule). film needs a PendularCheck after the interaction loop. Must be equal on both materials."))
		((std::string, formation, "contact", Attr::triggerPostLoad, "liquid='film': a bridge forms at contact (contact, the default) or when the liquid films touch (films: gap <= h1 + h2, h the film thickness of Elskamp2018 eq. 34, film/filmArea on a wall; the pair must be detected that far, e.g. interactionDetectionFactor of Bo1 and Ig2; YADE's wall and facet geometry exists at contact only). Must be equal on both materials."))
		((std::string, transfer, "exact", Attr::triggerPostLoad, "liquid='film': how a breaking bridge's liquid goes back to the two films: exact (the Young-Laplace solver's split at the neck at the exact rupture, tabulated on young_laplace_table's nodes: equal contact angles, R_small/R_large >= 1/4 or a wall), parabolic (Elskamp2018 eq. 35-43 at the rupture distance) or diameter (Richefeu2008: R1/(R1 + R2)). A wall that holds no film (filmArea = 0) leaves all of it to the sphere. Must be equal on both materials."))
		((bool, extrapolate, false, Attr::triggerPostLoad, "False: a bridge outside its model's validity domain (V*, contact angle, size ratio; yade_capillary.kernels.models()) is an error. True: the model is evaluated at the nearest point of its domain, stretched to the bridge's rupture distance and scaled by R cos(theta) (finite, non-negative, monotone where the model is). Must be equal on both materials.")),
		createIndex(); lastGood = checked();
	);
	// clang-format on
	REGISTER_CLASS_INDEX(PendularMat, Material);
};
REGISTER_SERIALIZABLE(PendularMat);

class PendularPhys : public NormShearPhys {
public:
	capillary::Bridge bridge {}; // per-bridge invariants, rebuilt from the attributes by postLoad
	// Likewise for eta > 0 (null otherwise: an inviscid bridge carries a pointer, not the invariants).
	std::shared_ptr<const capillary::ViscousBridge> viscous;
	void              postLoad(PendularPhys&);
	void              buildBridge();
	// The viscous forces (eta > 0) of a bridge of this pair holding `volume` [m^3].
	std::shared_ptr<const capillary::ViscousBridge> viscousOf(Real volume) const;
	std::string       modelName() const;
	std::string       ruptureName() const;
	std::string       calibrateName() const;
	std::string       viscousName() const;
	std::string       transferName() const;
	bool              extrapolated() const { return bridge.extrapolated(); }
	virtual ~PendularPhys() = default;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularPhys, NormShearPhys,
		"Interaction physics of :yref:`PendularMat`: contact parameters and one liquid bridge. State machine: no bridge -> "
		"formed at the first contact (``active``) -> broken beyond ``sCrit`` (the interaction is then removed, so a new bridge "
		"needs a new contact). ``normalForce`` includes the capillary force.",
		((Real, cn, 0, Attr::readonly, "Normal damping [N s/m]."))
		((Real, cs, 0, Attr::readonly, "Tangential damping [N s/m]."))
		((Real, tangensOfFrictionAngle, 0, Attr::readonly, "Tangent of the contact friction angle [-]."))
		((bool, wet, false, Attr::readonly, "Both materials are wet: a bridge forms at contact."))
		((bool, active, false, Attr::readonly, "A liquid bridge exists (formed at contact, not yet broken)."))
		((bool, film, false, Attr::readonly, "The bridge's liquid comes from the bodies' films (PendularMat.liquid = 'film'); Vb is 0 until it forms."))
		((bool, filmFormation, false, Attr::readonly, "film: the bridge forms when the films touch (PendularMat.formation = 'films'), else at contact."))
		((bool, pending, false, Attr::readonly, "film: the bridge was asked for in this step; PendularCheck forms it at the end of the step."))
		((bool, forceInContact, false, Attr::readonly, "F(0) acts during overlap."))
		((Real, R1, 0, Attr::readonly, "Radius of the (first) sphere of the bridge [m]: body 1, or body 2 if body 1 is a wall or facet (swapped)."))
		((Real, R2, 0, Attr::readonly, "Radius of the other body [m] (inf for a wall or facet)."))
		((Real, Vb, 0, Attr::readonly, "Liquid bridge volume [m^3]."))
		((Real, gamma, 0, Attr::readonly, "Surface tension [N/m]."))
		((Real, theta1, 0, Attr::readonly, "Contact angle on body 1 [rad]."))
		((Real, theta2, 0, Attr::readonly, "Contact angle on body 2 [rad]."))
		((int, modelIndex, -1, Attr::readonly, "Index of the capillary model of this bridge in yade_capillary.kernels.MODEL_NAMES (resolved once, at creation; -1: no bridge); its name is ``model``."))
		((int, ruptureIndex, -1, Attr::readonly, "Index of the rupture rule in yade_capillary.kernels.RUPTURE_NAMES; its name is ``rupture``."))
		((int, calibrateIndex, -1, Attr::readonly, "linear_irreversible: index of the reference model of the calibration; its name is ``calibrateFrom``."))
		((bool, extrapolate, false, Attr::readonly, "The bridge may be outside its model's domain (PendularMat.extrapolate)."))
		((Real, linearFmax, 0, Attr::readonly, "linear_irreversible: maximum force as given [N] (0: calibrated)."))
		((Real, linearKc, 0, Attr::readonly, "linear_irreversible: stiffness as given [N/m] (0: calibrated)."))
		((Real, R, 0, Attr::readonly, "Effective radius 2R1R2/(R1+R2) [m]; 2R for a wall (Derjaguin sphere-plane limit)."))
		((Real, sCrit, 0, Attr::readonly, "Rupture distance: largest surface gap of the bridge [m]."))
		((Real, force0, 0, Attr::readonly, "Capillary force at contact F(0) [N]."))
		((Real, Fcap, 0, Attr::readonly, "Capillary force of the last step [N], positive = attraction."))
		((Real, eta, 0, Attr::readonly, "Liquid viscosity [Pa s] (0: no viscous force)."))
		((Real, viscousSmin, 0, Attr::readonly, "S_min / r* of the viscous forces [-]."))
		((int, viscousIndex, -1, Attr::readonly, "Index of the normal viscous law in yade_capillary.kernels.VISCOUS_NAMES (-1: no viscous force); its name is ``viscousNormal``."))
		((bool, dynamicRupture, false, Attr::readonly, "The rupture distance is stretched by Pitois' rule (Elskamp2018 eq. 33)."))
		((bool, swapped, false, Attr::readonly, "Body 1 is the wall or facet: R1 is the radius of body 2."))
		((Real, Fvisc, 0, Attr::readonly, "Normal viscous force of the last step [N], positive = attraction (separating); included in normalForce."))
		((Vector3r, viscousShear, Vector3r::Zero(), Attr::readonly, "Tangential viscous force on body 2 of the last step [N] (Elskamp2018 eq. 28, 29); not part of shearForce, which is the tangential spring."))
		((Real, sRupture, 0, Attr::readonly, "Rupture distance of the last step [m]: sCrit, stretched by the dynamic rule if dynamicRupture."))
		((int, transferIndex, -1, Attr::readonly, "film: index of the transfer rule in yade_capillary.kernels.TRANSFER_NAMES (-1: fixed volume); its name is ``transfer``."))
		((Real, transfer1, 0, Attr::readonly, "film: the share of Vb that goes back to the sphere of radius R1 at rupture [-] (the rest to the other body, or to the sphere too if that is a wall holding no film)."))
		((Real, VbMin, 0, Attr::readonly, "film: smallest bridge volume [m^3]: the smallest V* of the model's domain (and of the exact transfer table) times R^3."))
		((Real, VbMax, 0, Attr::readonly, "film: largest bridge volume [m^3]: Vb of the materials, and the largest V* of the model's domain (and of the exact transfer table) times R^3.")),
		createIndex();,
		.add_property("model", &PendularPhys::modelName, "Name of the capillary model of this bridge ('' without bridge).")
		.add_property("rupture", &PendularPhys::ruptureName, "Name of the rupture rule of this bridge.")
		.add_property("calibrateFrom", &PendularPhys::calibrateName, "linear_irreversible: name of the reference model of the calibration.")
		.add_property("extrapolated", &PendularPhys::extrapolated, "The bridge lies outside its model's domain and is extrapolated.")
		.add_property("viscousNormal", &PendularPhys::viscousName, "Name of the normal viscous law ('' without viscosity).")
		.add_property("transfer", &PendularPhys::transferName, "film: name of the transfer rule ('' for a fixed volume).")
	);
	// clang-format on
	REGISTER_CLASS_INDEX(PendularPhys, NormShearPhys);
};
REGISTER_SERIALIZABLE(PendularPhys);

class Ip2_PendularMat_PendularMat_PendularPhys : public IPhysFunctor {
public:
	void go(const shared_ptr<Material>& m1, const shared_ptr<Material>& m2, const shared_ptr<Interaction>& I) override;
	// Two-body critical time step [s] of bodies id1 and id2 of the current scene, whatever their distance.
	Real criticalDt(Body::id_t id1, Body::id_t id2);
	// For PendularCheck, in serial code: the first input error met in the current step of `scene`
	// ("" if none; an error of an earlier step or another scene is dropped), and the smallest
	// critical time step of the interactions created since the last call (inf if none).
	std::string takeError(Scene* scene);
	struct PairDt {
		Real       dt;
		Body::id_t id1, id2; // the pair that has it (-1 if none)
	};
	PairDt takeCriticalDt();
	FUNCTOR2D(PendularMat, PendularMat);
	DECLARE_LOGGER;

private:
	void setContact(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void setLiquid(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void setFilm(const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const;
	void report(const std::string& message, const Interaction& I);
	// Written from InteractionLoop's OpenMP threads, hence the locks.
	std::mutex  errorMutex, dtMutex;
	bool        errorPending = false;
	std::string error;
	Scene*      errorScene       = nullptr;
	long        errorIter        = -1;
	long        stopAtIterBefore = 0;
	PairDt      newCriticalDt { std::numeric_limits<Real>::infinity(), -1, -1 };

public:
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(Ip2_PendularMat_PendularMat_PendularPhys, IPhysFunctor,
		"Creates :yref:`PendularPhys` from two :yref:`PendularMat`. Mixing rules: tc, en, et arithmetic means; kn, cn, ks, cs "
		"in series; friction angle the smaller; Vb and gamma arithmetic means; contact angles kept per body; model, rupture rule, "
		"forceInContact and linear parameters must be equal (else an error). Effective mass m1 m2/(m1+m2), where a body that is "
		"not dynamic counts as infinitely heavy (unless neither is dynamic). A body whose shape is not a Sphere (wall, facet) "
		"is a plane for the bridge. Input errors are raised by :yref:`PendularCheck`: if only the liquid is wrong, the pair "
		"gets the contact law without a bridge; if the contact parameters are wrong, the interaction is reset and the error "
		"comes again at every step.",
		/*attrs*/,
		/*ctor*/,
		.def("criticalDt", &Ip2_PendularMat_PendularMat_PendularPhys::criticalDt, (boost::python::arg("id1"), boost::python::arg("id2")),
		     "Two-body critical time step [s] of bodies id1 and id2 of the current scene (their contact parameters and masses, "
		     "whatever their distance): the stability limit of YADE's leapfrog for the normal and the tangential spring-dashpot, "
		     "dt_c = (2/w0)(sqrt(1+z^2) - z), w0^2 = k/m, z = c/(2 sqrt(k m)); tangential mass 1/(1/m + r^2/I) per dynamic sphere. "
		     "See yade_capillary.scene.stable_dt.")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(Ip2_PendularMat_PendularMat_PendularPhys);

class Law2_ScGeom_PendularPhys_Bridge;

class PendularCheck : public GlobalEngine {
	Real warnedDt = NaN; // O.dt of the last warning
	// The overlap check's bound as last handed to the laws, and the body count it was computed for
	// (see Law2_ScGeom_PendularPhys_Bridge::overlapAlarm).
	Real   alarmBound  = NaN;
	size_t alarmBodies = 0;
	bool   overlapWarned = false;
	// Hands maxOverlap to `law` and takes what its contacts reported (see action()).
	void checkOverlaps(Law2_ScGeom_PendularPhys_Bridge& law, bool fresh);
	// The step's dt check: warns (again if newPair lowered the limit), or with adaptDt lowers O.dt;
	// returns an input error ("" if none).
	std::string checkDt(bool newPair);

public:
	// Wraps yade.wrapper's Omega.run and Omega.wait, once, so that they raise an error of this
	// engine that YADE's wait() missed (see deliverMissed in Pendular.cpp), and the erase and clear
	// of BodyContainer and InteractionContainer, so that the liquid they remove is accounted for.
	// Called by yade_capillary.patches.install, which lists every patch of YADE's Python objects.
	static void installGuards();
	void        action() override;
	// Raises `message` from a step of `scene` as PendularCheck's errors are raised: a ValueError in
	// Python, also when YADE's wait() misses it, and under mpiexec the end of every rank.
	static void raiseInStep(Scene* scene, const std::string& message);
	DECLARE_LOGGER;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularCheck, GlobalEngine,
		"Raises (as a Python ValueError from O.step, O.run(n, True) and O.wait) the first input error that "
		":yref:`Ip2_PendularMat_PendularMat_PendularPhys` met while creating interactions in this step of this scene, e.g. two "
		"materials with different models or a bridge outside its model's domain, and warns (once per value of O.dt) when O.dt "
		"exceeds dtSafety times the smallest two-body critical time step of the interactions created so far. Place it right "
		"after the InteractionLoop (yade_capillary.scene.engines does). Without it, an input error stops the simulation at the "
		"end of the step and is logged. installGuards (called by yade_capillary.patches.install, which yade_capillary.scene.engines "
		"calls) wraps Omega.run and Omega.wait so that they raise the error also when it "
		"stopped the simulation thread before YADE's wait() looked (which then returns without it), and O.bodies.erase and clear, "
		"O.interactions.erase and clear to account for the liquid they remove; it warns at its first step when they are not wrapped. "
		"With liquid='film' it also forms the bridges asked for in the step and moves the liquid of broken bridges to the films "
		"(Law2_ScGeom_PendularPhys_Bridge.settleFilms).",
		((Real, dtSafety, 0.3, , "Warn when O.dt > dtSafety * criticalDt [-], (0, 1]. 0.3 ~ 1/sqrt(12): a sphere with 12 contacts can have a highest frequency up to sqrt(12) times that of one contact (Gershgorin's bound)."))
		((Real, criticalDt, std::numeric_limits<Real>::infinity(), Attr::readonly, "Smallest two-body critical time step of the interactions created so far [s] (see Ip2_PendularMat_PendularMat_PendularPhys.criticalDt: with the viscous forces of the pair's bridge, in film mode of the largest bridge it can form); inf before the first."))
		((Vector2i, criticalPair, Vector2i(-1, -1), Attr::readonly, "The two bodies of the interaction that has criticalDt [-]; (-1, -1) before the first."))
		((long, dtWarnings, 0, Attr::readonly, "Number of time-step warnings given [-]."))
		((bool, adaptDt, false, , "When O.dt exceeds dtSafety * criticalDt (a new pair, e.g. a viscous bridge of small spheres, has a smaller limit), lower O.dt to dtSafety * criticalDt and log it, instead of only warning [-]. Off by default: YADE users expect O.dt to change only when they change it. Refused under yade.mpy with several ranks (each rank would change its own O.dt)."))
		((long, dtAdaptations, 0, Attr::readonly, "Number of times adaptDt lowered O.dt [-]."))
		((Real, maxOverlap, 0.5, , "Warn (once, with the pair, the overlap, the estimated impact speed and a tc that would keep the overlap below this bound) when a contact's overlap exceeds maxOverlap times the smaller radius of the pair [-], (0, 2]. A contact given by tc overlaps about v tc / pi at impact speed v, so fast collisions of small spheres may overlap by more than their radius. Costs one comparison per contact-step. A change takes effect from the step after the next."))
		((long, nOverlaps, 0, Attr::readonly, "Number of contact-steps whose overlap exceeded maxOverlap times the pair's smaller radius [-] (pairs of two bodies that do not move are not counted)."))
		((Real, largestOverlap, 0, Attr::readonly, "Largest overlap counted in nOverlaps, divided by the pair's smaller radius [-]; 0 if none.")),
		/*ctor*/,
		.def("installGuards", &PendularCheck::installGuards, "Wrap Omega.run, Omega.wait, O.bodies.erase and clear, O.interactions.erase and clear (once per process; see the class). yade_capillary.patches.install calls it.")
		.staticmethod("installGuards")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularCheck);

// Positions and velocities of the two bodies of an interaction, as the contact law reads them;
// shift2 and shiftVel move body 2 to its periodic image (zero without periodic cell). owned: this
// scene counts the bridge in the law's totals (see pendularOwner). id1, id2: the bodies, whose films
// a film-mode bridge reads when it forms and breaks.
struct PendularKinematics {
	const Vector3r &pos1, &vel1, &angVel1, &pos2, &vel2, &angVel2;
	const Vector3r &shift2, &shiftVel; // references, as the others: a copy per bridge-step cost six stores
	bool            owned;
	Body::id_t      id1, id2;
};

// yade.mpy computes an interaction between bodies of two subdomains on both ranks: its bridge is
// counted in the totals (nBridges, liquidVolume, ...) only by the rank of the larger subdomain
// number, so that the sum over ranks counts every bridge once (the master, subdomain 0, keeps the
// walls; a wall-sphere pair belongs to the sphere's rank). Without MPI every subdomain is 0.
inline bool pendularOwner(int sceneSubdomain, int subdomain1, int subdomain2) { return sceneSubdomain == math::max(subdomain1, subdomain2); }

class Law2_ScGeom_PendularPhys_Bridge : public LawFunctor {
public:
	bool go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I) override;
	// The contact law of one interaction: updates phys and the bridge totals, hands the force to
	// `sink` (body 1 gets -f, body 2 +f) and returns false when the interaction is to be reset.
	// Used by go() (YADE's InteractionLoop) and by PendularLoop, so both compute the same numbers.
	// Sink: force(f) for a central force, forceTorque(f, t1, t2) with the torques on bodies 1, 2.
	// rotate(v): ScGeom::rotate, the shear force carried from the last contact plane to this one.
	// Geom, Phys: ScGeom and PendularPhys, or PendularLoop's record of a fixed-volume inviscid
	// sphere-sphere bridge, which has their members of the same names (see PendularLoop::Record).
	template <class Geom, class Phys, class Rotate, class Sink>
	bool apply(const Geom& geom, Phys& phys, const PendularKinematics& k, Real dt, const Rotate& rotate, Sink& sink);
	// Breaks the bridge (totals if owned; film: its liquid back to the films at the end of the step)
	// and returns false: the interaction is to be reset.
	template <class Phys> bool breakBridge(Phys& phys, const PendularKinematics& k);
	// Film mode, at the end of each step (PendularCheck, serial): forms the bridges asked for in the
	// step, sharing each film among all the bridges formed on it (Elskamp2018 section 2.2.1), then
	// adds the liquid of the bridges broken in the step to the films. Throws std::invalid_argument if
	// a bridge could not be built (after settling all others, so that no liquid is lost).
	void settleFilms(Scene* scene);
	// The Python paths that remove bodies or interactions (wrapped by PendularCheck::installGuards):
	// releasePair breaks an active bridge as at rupture, its liquid to the two films (O.interactions.erase
	// and clear); eraseBody breaks the body's bridges and moves its film to liquidRemoved, with its clump's
	// members if clumpMembers (O.bodies.erase); clearBodies moves all liquid to liquidRemoved
	// (O.bodies.clear). Refused (std::runtime_error) while the simulation runs.
	void releasePair(Scene* scene, Interaction& I);
	void eraseBody(Scene* scene, Body::id_t id, bool clumpMembers);
	void clearBodies(Scene* scene);
	boost::python::dict liquidTotals() const;
	// Gives the real interaction id1-id2 of the current scene the bridge of its physics, counted in
	// the totals as at a first contact, for a bridge of a saved state (shearcell.load_state), up to a gap
	// of the rupture distance + pastRupture [m]: a state saved after Newton's half of a step may hold a
	// bridge that the step stretched past rupture and that the law breaks at the next step.
	// std::invalid_argument (ValueError) naming what does not allow it.
	void formBridge(Body::id_t id1, Body::id_t id2, Real pastRupture);
	// liquidVolume is a running sum: with no bridge left its round-off is set to exactly 0.
	void zeroEmptyTotals();

	// The overlap check (PendularCheck.maxOverlap). apply() compares a contact's overlap with
	// overlapAlarm, maxOverlap times the smallest sphere radius of the scene (inf: off), which
	// PendularCheck sets: one comparison per contact-step. The rare contact above it is measured
	// against its own smaller radius by overlapSeen, out of line.
	Real overlapAlarm = std::numeric_limits<Real>::infinity();
	Real overlapBound = 0.5; // maxOverlap [-]
	struct OverlapReport {
		long       count   = 0; // contact-steps above the bound
		Real       largest = 0; // overlap / smaller radius of the largest
		Body::id_t id1 = -1, id2 = -1;
		Real       overlap = 0, radius = 0, speed = 0; // of the largest [m], [m], [m/s]
	};
	// What the contacts reported since the last call, reset.
	OverlapReport takeOverlaps();

private:
	// Scalars only: a reference to the kinematics or the geometry would make the hot path keep them in
	// memory at every bridge-step; the rare call finds the rest from the bodies and the interaction.
	__attribute__((noinline, cold)) void overlapSeen(Real depth, Body::id_t id1, Body::id_t id2, Real kn);
	std::mutex    overlapMutex;
	OverlapReport overlaps;
	// Film mode: what the bridges ask of the films in a step, done by settleFilms. Rare (formation and
	// rupture only), so one lock for InteractionLoop's threads.
	struct FilmFormation {
		PendularPhys* phys;
		Body::id_t    id1, id2;
		Real          take1, take2; // Shi & McCarthy's volumes from the films of bodies id1, id2 [m^3]
		bool          owned;
	};
	struct FilmReturn {
		Body::id_t id;
		Real       volume;
	};
	std::mutex                 filmMutex;
	std::vector<FilmFormation> formations;
	std::vector<FilmReturn>    returns;
	// The sphere R1 of a bridge and its other body (a sphere R2, or a wall or facet): bodies 1 and 2
	// unless swapped.
	struct FilmPair {
		Body::id_t sphere, other;
	};
	static FilmPair filmPair(const PendularPhys& p, Body::id_t id1, Body::id_t id2) { return p.swapped ? FilmPair { id2, id1 } : FilmPair { id1, id2 }; }
	// What goes back to the sphere R1 when the bridge ends [m^3]: transfer1 of its liquid, or all of it
	// if the other body is a wall that holds no film (otherHolds false); the other body gets the rest.
	static Real sphereShare(const PendularPhys& p, bool otherHolds) { return otherHolds ? p.transfer1 * p.Vb : p.Vb; }
	void                       askFormation(PendularPhys& phys, const PendularKinematics& k);
	bool                       filmsTouch(const PendularPhys& phys, const PendularKinematics& k, Real gap) const;

public:
	FUNCTOR2D(ScGeom, PendularPhys);
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(Law2_ScGeom_PendularPhys_Bridge, LawFunctor,
		"Contact law of yade-capillary. In contact: linear viscoelastic normal force without attraction while unloading, "
		"incremental tangential spring-dashpot with Coulomb friction (Gladkyy2014 eq. 3-4), plus F(0) if forceInContact. "
		"Separated with a bridge: the capillary force of the bridge's model along the line of centres; beyond the rupture "
		"distance the bridge breaks and the interaction is removed. Separated without a bridge (before the first contact, "
		"with a detection factor > 1): no force, and the interaction is reset (returns false), so that it is removed once "
		"the bounding boxes part and made again at contact; a real interaction keeps its geometry until the law ends it, so "
		"no enlarged detection range is needed for the bridge.",
		((OpenMPAccumulator<int>, nBridges, , Attr::readonly, "Number of liquid bridges that exist now [-]. Saved by O.save. Under yade.mpy, the bridges of this rank (a bridge between two subdomains belongs to the larger subdomain number); yade_capillary.mpi.liquid_totals() sums over ranks."))
		((OpenMPAccumulator<Real>, liquidVolume, , Attr::readonly, "Liquid volume in the bridges that exist now [m^3]. Saved by O.save."))
		((OpenMPAccumulator<Real>, liquidFormed, , Attr::readonly, "Liquid volume put into bridges since the start [m^3] (fixed volume per bridge, Gladkyy2014). Saved by O.save."))
		((OpenMPAccumulator<Real>, liquidReleased, , Attr::readonly, "Liquid volume of bridges broken since the start [m^3]; liquidFormed - liquidReleased = liquidVolume. Saved by O.save."))
		((Real, liquidRemoved, 0, Attr::readonly, "liquid='film': liquid that left the scene with erased bodies (O.bodies.erase) [m^3]: their films and their shares of their bridges. films + bridges + liquidRemoved is constant (liquidTotals()). Saved by O.save.")),
		/*ctor*/,
		/*py*/
		.def("formBridge", &Law2_ScGeom_PendularPhys_Bridge::formBridge, (boost::python::arg("id1"), boost::python::arg("id2"), boost::python::arg("pastRupture") = 0.0),
		     "Form the bridge of the real interaction id1-id2 of the current scene, as at its first contact (nBridges, liquidVolume "
		     "and liquidFormed count it), whatever the gap up to the rupture distance + pastRupture [m] (>= 0; a saved bridge that the "
		     "step before the save stretched past its rupture distance, which the law breaks at the next step): restores a bridge of "
		     "a saved state (shearcell.load_state). Only for a wet fixed-volume pair without a bridge, not while the simulation runs; "
		     "ValueError otherwise.")
		.def("liquidTotals", &Law2_ScGeom_PendularPhys_Bridge::liquidTotals, "The liquid of the current scene [m^3] as a dict: films (sum of PendularState.film over the bodies), bridges (sum of Vb over the film-mode bridges that exist), removed (liquidRemoved), total (their sum, constant in film mode) and fixedBridges (the bridges of fixed-volume materials, not part of total)."));
	// clang-format on
};
REGISTER_SERIALIZABLE(Law2_ScGeom_PendularPhys_Bridge);

// The viscous terms of a bridge with eta > 0 at the surface separation S (Elskamp2018 eq. 25-29),
// through the bridge's capillary::ViscousBridge: sets phys.Fvisc, phys.viscousShear and
// phys.sRupture (eq. 33 if dynamicRupture) and returns the moments on bodies 1 and 2.
// Velocities: the centres of the spheres (Elskamp2018 after eq. 25), a wall's or facet's velocity
// at the contact point, which has no radius to turn its rotation into a surface velocity (its arm
// is 0 in omega_r = r1 omega1 + r2 omega2). Moments: r n x F1 on a sphere (Elskamp2018 after eq. 6;
// for separated spheres the two do not balance the couple of the pair of forces, a property of the
// paper's model); a wall or facet gets the moment of its force at the contact point.
struct PendularViscousMoments {
	Vector3r torque1, torque2;
};
inline PendularViscousMoments pendularViscous(const ScGeom& geom, PendularPhys& phys, const PendularKinematics& k, Real S)
{
	const bool     wall1 = phys.swapped, wall2 = !phys.swapped && math::isinf(phys.R2);
	const Real     arm1 = wall1 ? 0 : phys.R1, arm2 = wall1 ? phys.R1 : (wall2 ? 0 : phys.R2);
	Vector3r       v1 = k.vel1, v2 = k.vel2 + k.shiftVel;
	if (wall1) v1 += k.angVel1.cross(geom.contactPoint - k.pos1);
	if (wall2) v2 += k.angVel2.cross(geom.contactPoint - k.pos2 - k.shift2);
	const Vector3r& n    = geom.normal; // from body 1 to body 2
	const Vector3r  vRel = v1 - v2;
	const Real      vn   = n.dot(vRel); // > 0: approaching
	double          ct, cr;
	bool            near;
	phys.viscous->tangential_coefficients(S, ct, cr, near);
	const Vector3r force1 = capillary::tangential_viscous_force(ct, cr, n, Vector3r(vRel - vn * n), Vector3r(arm1 * k.angVel1 + arm2 * k.angVel2));
	phys.Fvisc            = -phys.viscous->normal_coefficient(S) * vn; // F1 = -c v_n n, so body 2 gets -Fvisc n
	phys.viscousShear     = -force1;
	phys.sRupture         = phys.dynamicRupture ? phys.bridge.rupture * phys.viscous->rupture_stretch(vRel.norm()) : phys.bridge.rupture;
	const Vector3r nxF1   = n.cross(force1); // M1 = r1 n x F1, M2 = r2 n x F1 (Elskamp2018 after eq. 6)
	return { wall1 ? Vector3r((geom.contactPoint - k.pos1).cross(force1)) : Vector3r(arm1 * nxF1),
		 wall2 ? Vector3r((geom.contactPoint - k.pos2 - k.shift2).cross(-force1)) : Vector3r(arm2 * nxF1) };
}

// Only a PendularPhys can hold a film-mode or viscous bridge; PendularLoop's records hold the others.
template <class Phys> constexpr bool pendularFullPhys = std::is_same<Phys, PendularPhys>::value;

template <class Phys> inline bool Law2_ScGeom_PendularPhys_Bridge::breakBridge(Phys& phys, const PendularKinematics& k)
{
	phys.active = false;
	phys.Fcap   = 0;
	if (k.owned) {
		nBridges -= 1;
		liquidVolume -= phys.Vb;
		liquidReleased += phys.Vb;
	}
	if constexpr (pendularFullPhys<Phys>) {
		phys.Fvisc        = 0;
		phys.viscousShear = Vector3r::Zero();
		if (phys.film) {
			// Whether the other body holds a film is read now: filmArea may have changed since the bridge formed.
			const FilmPair ids        = filmPair(phys, k.id1, k.id2);
			const auto*    otherState = static_cast<const PendularState*>(Body::byId(ids.other, scene)->state.get());
			const Real     toSphere   = sphereShare(phys, otherState->holds(phys.R2));
			const std::lock_guard<std::mutex> lock(filmMutex);
			returns.push_back({ ids.sphere, toSphere });
			returns.push_back({ ids.other, phys.Vb - toSphere });
		}
	}
	return false;
}

template <class Geom, class Phys, class Rotate, class Sink>
inline bool Law2_ScGeom_PendularPhys_Bridge::apply(
        const Geom& geom, Phys& phys, const PendularKinematics& k, Real dt, const Rotate& rotate, Sink& sink)
{
	constexpr bool full = pendularFullPhys<Phys>; // else no film and no viscosity
	if (geom.penetrationDepth < 0) { // separated
		phys.shearForce = Vector3r::Zero();
		if (!phys.active) {
			phys.normalForce = Vector3r::Zero();
			// Film mode, formation when the films touch: the pair is kept while they do.
			if constexpr (full)
				if (phys.filmFormation && filmsTouch(phys, k, -geom.penetrationDepth)) {
					if (!phys.pending) askFormation(phys, k);
					return true;
				}
			// No bridge yet (or dry): nothing to keep. Returning false resets the interaction, so the
			// collider removes it once the bounding boxes part, and the Ig2 makes it real again at
			// contact, where the bridge forms; a pair that stays close merely gets new physics.
			return false;
		}
		const Real gap = -geom.penetrationDepth;
		if constexpr (full)
			if (phys.viscous) {
				const PendularViscousMoments m = pendularViscous(geom, phys, k, gap);
				if (gap > phys.sRupture) return breakBridge(phys, k);
				phys.Fcap        = capillary::bridge_force_within(phys.bridge, gap, phys.sRupture);
				phys.normalForce = -(phys.Fcap + phys.Fvisc) * geom.normal;
				sink.forceTorque(phys.normalForce + phys.viscousShear, m.torque1, m.torque2);
				return true;
			}
		// An inviscid separated bridge needs only the gap and the normal: no tangential work, no torque.
		if (gap > phys.bridge.rupture) return breakBridge(phys, k);
		phys.Fcap        = capillary::bridge_force(phys.bridge, gap);
		phys.normalForce = -phys.Fcap * geom.normal;
		sink.force(phys.normalForce);
		return true;
	}

	// kn = 0 only if the Ip2 rejected the contact parameters: reset, so that its error comes again.
	if (!(phys.kn > 0)) return false;
	if (__builtin_expect(geom.penetrationDepth > overlapAlarm, 0)) overlapSeen(geom.penetrationDepth, k.id1, k.id2, phys.kn);
	// In contact. The bridge forms at the first contact (Gladkyy2014 section 2).
	if (phys.wet && !phys.active) {
		bool film = false;
		if constexpr (full) film = phys.film;
		if (!film) {
			phys.active = true;
			if (k.owned) {
				nBridges += 1;
				liquidVolume += phys.Vb;
				liquidFormed += phys.Vb;
			}
		} else if constexpr (full)
			if (!phys.pending) askFormation(phys, k); // formed by settleFilms at the end of the step
	}
	bool twoSpheres = true; // a record is always a sphere-sphere pair
	if constexpr (full) twoSpheres = !phys.swapped && math::isfinite(phys.R2);
	bool viscous = false; // the bridge's viscous forces also act in contact, at S_eff = S_min
	if constexpr (full) viscous = phys.viscous && phys.active;
	phys.Fcap = (phys.active && phys.forceInContact) ? phys.bridge.force0 : 0;
	// Gladkyy2014 eq. (3): linear spring-dashpot; no attraction while unloading (Schwager2007). vn > 0: approaching.
	const auto springDashpot = [&phys, &geom](Real vn) { return math::max(Real(0), phys.kn * geom.penetrationDepth + phys.cn * vn); };
	if (twoSpheres && !(phys.tangensOfFrictionAngle > 0) && !viscous) {
		// Frictionless between two spheres: a central force, from the overlap and the normal relative
		// velocity only. The spheres' rotations do not enter it (the arms from the centres to the contact
		// point lie along the normal, so omega x arm is normal to it), and the force has no moment about
		// either centre; so no contact point, arms or cross products (their round-off, in the other
		// branch, gives vn a part of 1e-16 and the spheres round-off torques that spin them).
		// By component: GCC leaves Eigen's assignment loop of this expression out of line (a call per bridge-step).
		const Vector3r dv(k.vel1[0] - k.vel2[0] - k.shiftVel[0], k.vel1[1] - k.vel2[1] - k.shiftVel[1], k.vel1[2] - k.vel2[2] - k.shiftVel[2]);
		const Real     fn = springDashpot(geom.normal.dot(dv));
		phys.shearForce    = Vector3r::Zero(); // the Coulomb cap is 0: no tangential spring or dashpot
		phys.normalForce   = (fn - phys.Fcap) * geom.normal;
		sink.force(phys.normalForce);
		return true;
	}
	const Vector3r c1x    = geom.contactPoint - k.pos1;
	const Vector3r c2x    = geom.contactPoint - k.pos2 - k.shift2;
	// Body 2's periodic image moves with vel2 + shiftVel (ScGeom::getIncidentVel).
	const Vector3r relVel = (k.vel1 + k.angVel1.cross(c1x)) - (k.vel2 + k.angVel2.cross(c2x)) - k.shiftVel;
	const Real     vn     = geom.normal.dot(relVel);
	const Real     fn     = springDashpot(vn);
	Vector3r&  shear = phys.shearForce;
	Vector3r   shearVisc = Vector3r::Zero();
	if (phys.tangensOfFrictionAngle > 0) {
		const Vector3r vs = relVel - vn * geom.normal;
		rotate(shear);
		shear += phys.ks * dt * vs;
		const Real maxFs = fn * phys.tangensOfFrictionAngle;
		if (shear.squaredNorm() > maxFs * maxFs) shear *= maxFs / shear.norm(); // Coulomb slip: elastic part capped, no viscous part
		else shearVisc = phys.cs * vs;
	} else {
		// Frictionless (Gladkyy2014: particle friction 0) with a wall or facet, or with a viscous
		// bridge: the Coulomb cap is 0, so the tangential spring and dashpot would be cut to zero anyway.
		shear = Vector3r::Zero();
	}
	if constexpr (full)
		if (viscous) {
			const PendularViscousMoments m = pendularViscous(geom, phys, k, -geom.penetrationDepth);
			phys.normalForce               = (fn - phys.Fcap - phys.Fvisc) * geom.normal;
			const Vector3r f               = phys.normalForce + shear + shearVisc; // acts at the contact point
			sink.forceTorque(f + phys.viscousShear, m.torque1 - c1x.cross(f), m.torque2 + c2x.cross(f));
			return true;
		}
	// A wall or facet keeps the moment of the force at the contact point about its own position.
	phys.normalForce = (fn - phys.Fcap) * geom.normal;
	const Vector3r f = phys.normalForce + shear + shearVisc;
	sink.forceTorque(f, -c1x.cross(f), c2x.cross(f));
	return true;
}

} // namespace yade
