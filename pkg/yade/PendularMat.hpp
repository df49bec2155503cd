// PendularMat: the material of yade-capillary, its attributes and their checks.
#pragma once

#include "AttrSnapshot.hpp"
#include "PendularState.hpp"
#include "YadeHeaders.hpp"
#include "models.hpp"
#include "transfer.hpp"
#include "viscous.hpp"

#include <string>

namespace yade {

// PendularMat's attributes, one list for YADE_CLASS_BASE_DOC_ATTRS_CTOR and for the snapshot that
// undoes a refused assignment (AttrSnapshot.hpp).
// clang-format off
#define PENDULAR_MAT_ATTRS \
	((Real, tc, NaN, Attr::triggerPostLoad, "Contact duration [s], (0, inf); NaN if kn, cn, ks, cs are given. The normal stiffness and damping make the half period of the damped oscillation equal to tc.")) \
	((Real, en, NaN, Attr::triggerPostLoad, "Normal restitution coefficient [-], (exp(-2), 1]. Exact for a binary collision including the rule that the contact never attracts (Schwager & Poeschel 2007), unlike the textbook formula.")) \
	((Real, et, NaN, Attr::triggerPostLoad, "Tangential restitution coefficient [-], (0, 1]; sets ks = 2/7 kn-equivalent and cs as in YADE's ViscElMat.")) \
	((Real, kn, NaN, Attr::triggerPostLoad, "Normal stiffness of this material [N/m], (0, inf); two materials combine in series. NaN if tc, en, et are given.")) \
	((Real, cn, NaN, Attr::triggerPostLoad, "Normal damping of this material [N s/m], [0, inf); combined in series.")) \
	((Real, ks, NaN, Attr::triggerPostLoad, "Tangential stiffness of this material [N/m], [0, inf); combined in series.")) \
	((Real, cs, NaN, Attr::triggerPostLoad, "Tangential damping of this material [N s/m], [0, inf); combined in series.")) \
	((Real, frictionAngle, 0.5, Attr::triggerPostLoad, "Contact friction angle [rad], [0, pi/2); the smaller of two materials is used.")) \
	((Real, rollingFriction, 0, Attr::triggerPostLoad, "Rolling friction mu_roll [m], [0, inf) (Elskamp2018 Table 3): in contact, a moment of constant magnitude mu_roll f_n against the relative rolling (the relative angular velocity without its part along the normal), f_n the contact part of the normal force. 0 (the default): none, at no cost. Two materials: arithmetic mean.")) \
	((std::string, normalDamping, "always", Attr::triggerPostLoad, "When the normal dashpot acts: always (the default: approaching and separating, the contact force floored at 0, Gladkyy2014 eq. 3 with Schwager & Poeschel 2007) or approach (only while the particles approach, Richefeu2008 eq. 3: no dissipation while unloading; en then gives the damping by the restitution of that law, en in (exp(-1), 1]). Must be equal on both materials.")) \
	((std::string, friction, "spring", Attr::triggerPostLoad, "Tangential contact force: spring (the default: incremental tangential spring ks and dashpot cs, capped by Coulomb, Gladkyy2014 eq. 4) or viscous (Richefeu2008 eq. 12: -min(cs |v_t|, mu f_n) v_t/|v_t| with the sliding velocity v_t and the contact part f_n of the normal force, the capillary force excluded; no spring, ks is not used, cs is the tangential viscosity gamma_t [N s/m]). Must be equal on both materials.")) \
	((bool, wet, false, Attr::triggerPostLoad, "True: liquid bridges form at contacts of two wet materials. Requires Vb > 0 and gamma > 0.")) \
	((Real, Vb, 0, Attr::triggerPostLoad, "Liquid bridge volume [m^3], (0, inf) when wet. Two materials: arithmetic mean. With liquid='film': the largest bridge volume (a larger Shi-McCarthy volume is capped, the rest stays on the films).")) \
	((Real, gamma, 0, Attr::triggerPostLoad, "Surface tension [N/m], (0, inf) when wet. Two materials: arithmetic mean.")) \
	((Real, theta, 0, Attr::triggerPostLoad, "Contact angle [rad], [0, pi/2). Two materials: each keeps its own; the force models use the angle whose cosine is the mean of the cosines (Elskamp2018 eq. 14-15, closer to the exact bridge than the mean angle), the lian and willett rupture rules the mean angle, willett_elskamp both.")) \
	((std::string, model, "willett_full", Attr::triggerPostLoad, "Capillary bridge model, one of:" CAPILLARY_MODEL_NAMES_LITERAL " (yade_capillary.kernels.models() lists each with its source and validity domain; young_laplace_table is the exact bridge, tabulated, with the exact rupture distance). A bridge outside its model's domain is refused unless extrapolate=True; a contact angle outside it is refused when the material is wet. Must be equal on both materials.")) \
	((std::string, rupture, "willett", Attr::triggerPostLoad, "Rupture rule: lian ((1+theta/2) V^(1/3)), willett (Gladkyy2014 eq. 2), willett_elskamp (Elskamp2018 eq. 32); linear_irreversible and young_laplace_table use their own range (fmax/kc, the exact rupture). Append +pitois (e.g. willett+pitois) for the dynamic rupture distance S_rup (1 + sqrt(|v1 - v2| eta/gamma)) (Pitois et al. 2001, Elskamp2018 eq. 33) on top of the static rule (or the model's own range); pitois alone means willett+pitois. +pitois needs eta > 0. Beyond the static distance the model's formula is continued, floored at 0 and capped at the force at the static distance (young_laplace_table keeps that force). Must mean the same rule on both materials.")) \
	((bool, forceInContact, false, Attr::triggerPostLoad, "True: the bridge force at contact F(0) also acts during overlap (Richefeu2008, Roy); False: it is off during overlap (Gladkyy2014 eq. 4). Must be equal on both materials.")) \
	((Real, linearFmax, 0, Attr::triggerPostLoad, "linear_irreversible: maximum adhesive force [N], (0, inf); 0 (with linearKc = 0) to calibrate from calibrateFrom.")) \
	((Real, linearKc, 0, Attr::triggerPostLoad, "linear_irreversible: adhesive stiffness [N/m], (0, inf); 0 (with linearFmax = 0) to calibrate from calibrateFrom.")) \
	((std::string, calibrateFrom, "willett_full", Attr::triggerPostLoad, "linear_irreversible: model whose maximum force and adhesive energy the linear law matches, per bridge (Roy section 4.2).")) \
	((Real, eta, 0, Attr::triggerPostLoad, "Dynamic viscosity of the liquid [Pa s], [0, 1e9]. 0 (the default): no viscous force is evaluated. > 0: a bridge adds the normal viscous force (viscousNormal) and Goldman's tangential force and moments (Elskamp2018 eq. 28, 29), in contact and separated. Two materials: arithmetic mean; both must be > 0 or both 0 (a wall left at 0 would halve the viscosity of its bridges).")) \
	((std::string, viscousNormal, "pitois", Attr::triggerPostLoad, "Normal viscous force with eta > 0: pitois (Pitois et al. 2000, Elskamp2018 eq. 26, finite bridge volume; the default) or adams_perchard (Elskamp2018 eq. 25). Must be equal on both materials.")) \
	((Real, viscousSmin, 0.001, Attr::triggerPostLoad, "S_min / r* [-], [1e-12, 1]: the viscous forces are evaluated at the separation max(S, 0) + S_min, S_min = viscousSmin r*, r* = R1 R2/(R1 + R2) (R1 for a wall), so that they stay finite at contact (Elskamp2018 after eq. 29: 0.001). Must be equal on both materials.")) \
	((std::string, liquid, "fixed", Attr::triggerPostLoad, "Where the liquid is: fixed (the default: each bridge has the volume Vb, created at formation and destroyed at rupture, Gladkyy2014) or film (the bodies carry it, PendularState.film: a bridge takes its volume from both films by Shi & McCarthy, Elskamp2018 eq. 7-10, capped at Vb and at the largest V* of the model's domain and of the exact transfer table; it forms one step after the pair qualifies, when PendularCheck has shared each film among all the bridges formed on it in that step, Elskamp2018 section 2.2.1; a volume below the smallest V* of those domains forms no bridge; at rupture the volume goes back to the two films by the transfer rule) or bonds (Richefeu2008 section 2.4: a PendularBonds engine shares all the liquid of the scene's bonds-mode bodies over every pair within the debonding distance, V_b = alpha R^3, and redistributes the liquid of broken bonds by its protocol; free liquid waits on the particles, PendularState.film, and a new contact takes all of it; the rupture rule must not be a model's own range, so not with linear_irreversible or young_laplace_table). film and bonds need a PendularCheck after the interaction loop, bonds also a PendularBonds after it. Must be equal on both materials.")) \
	((std::string, formation, "contact", Attr::triggerPostLoad, "liquid='film': a bridge forms at contact (contact, the default) or when the liquid films touch (films: gap <= h1 + h2, h the film thickness of Elskamp2018 eq. 34, film/filmArea on a wall; the pair must be detected that far, e.g. interactionDetectionFactor of Bo1 and Ig2; YADE's wall and facet geometry exists at contact only). Must be equal on both materials.")) \
	((std::string, transfer, "exact", Attr::triggerPostLoad, "liquid='film': how a breaking bridge's liquid goes back to the two films: exact (the Young-Laplace solver's split at the neck at the exact rupture, tabulated in young_laplace_table: V* = V/Rh^3 up to 0.5, either contact angle up to 70 deg, R_small/R_large >= 1/4 or a wall), parabolic (Elskamp2018 eq. 35-43 at the rupture distance) or diameter (Richefeu2008: R1/(R1 + R2)). A wall that holds no film (filmArea = 0) leaves all of it to the sphere. Must be equal on both materials.")) \
	((bool, extrapolate, false, Attr::triggerPostLoad, "False: a bridge outside its model's validity domain (V*, contact angle, size ratio; yade_capillary.kernels.models()) is an error. True: the model is evaluated at the nearest point of its domain, stretched to the bridge's rupture distance and scaled by R cos(theta) (finite, non-negative, monotone where the model is). Must be equal on both materials."))
// clang-format on

class PendularMat : public Material {
public:
	capillary::Model   modelId       = capillary::Model::willett_full; // resolved from `model` by postLoad
	capillary::Rupture ruptureId     = capillary::Rupture::willett;
	capillary::Model   calibrateId   = capillary::Model::willett_full;
	bool               dynamicRupture = false; // `rupture` ends with pitois (Elskamp2018 eq. 33)
	capillary::NormalViscous viscousId = capillary::NormalViscous::pitois;
	bool               filmMode      = false; // liquid == "film" or "bonds": the bodies hold the free liquid (PendularState.film)
	bool               bondsMode     = false; // liquid == "bonds" (Richefeu2008 section 2.4, PendularBonds)
	bool               filmFormation = false; // formation == "films"
	capillary::Transfer transferId   = capillary::Transfer::exact;
	bool               approachDamping = false; // normalDamping == "approach" (Richefeu2008 eq. 3)
	bool               viscousFriction = false; // friction == "viscous" (Richefeu2008 eq. 12)
	Real               dampingRatioN = 0; // beta/omega for `en` under normalDamping, see pendular::dampingRatioFor
	void               postLoad(PendularMat&);

private:
	// Attribute values after the last successful check: a rejected assignment is rolled back, so
	// one bad value does not make every later assignment fail.
	PENDULAR_ATTR_SNAPSHOT(PENDULAR_MAT_ATTRS)
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
		PENDULAR_MAT_ATTRS,
		createIndex(); lastGood = checked();
	);
	// clang-format on
	REGISTER_CLASS_INDEX(PendularMat, Material);
};
REGISTER_SERIALIZABLE(PendularMat);
#undef PENDULAR_MAT_ATTRS

namespace pendular {
	// An optional attribute of PendularMat (tc, en, et, kn, cn, ks, cs) is given: not NaN.
	inline bool isSet(Real x) { return !math::isnan(x); }
	// Schwager & Poeschel 2007: a linear spring-dashpot contact that is not allowed to attract
	// ends when the force reaches zero, before the overlap does; its restitution coefficient is
	// en = exp(-x (pi - 2 atan x)) with x = beta/omega (damping rate over damped frequency), not
	// the textbook exp(-pi x). Returns x for a given en in (exp(-2), 1] (the function is
	// increasing in x and tends to 2 as x -> infinity).
	// approachOnly (Richefeu2008 eq. 3, the dashpot acts only while approaching): the damped
	// approach ends at the largest overlap, omega t* = atan(1/x), and the undamped unloading returns
	// the elastic energy stored there, so en = exp(-beta t*) = exp(-x atan(1/x)); en in (exp(-1), 1]
	// (x atan(1/x) increases from 0 to 1).
	Real dampingRatioFor(Real en, bool approachOnly = false);
	// The smallest en (exclusive) of either normal damping.
	inline Real minRestitution(bool approachOnly) { return math::exp(Real(approachOnly ? -1 : -2)); }
} // namespace pendular

} // namespace yade
